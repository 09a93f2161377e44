#include "dfc/dem/distributed_simulation.hpp"

#include "dfc/common/state_archive.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>

#include "dfc/common/errors.hpp"
#include "dfc/dem/bond_state.hpp"
#include "dfc/dem/exact_sum.hpp"
#include "dfc/dem/uninitialised_allocator.hpp"
#include "dfc/dem/wall_forces.hpp"

namespace dfc::dem {

namespace {

static_assert(std::is_trivially_copyable_v<ParticleRecord>);

/// The most particles a box may hold, over the mean, before the boxes are cut
/// anew: 5 %, a small loss against the cost of gathering every position.
constexpr double rebalance_tolerance = 0.05;

using ByteBuffer = std::vector<std::byte, UninitialisedAllocator<std::byte>>;

/// Bytes for one destination, appended to and read in order. Uninitialised
/// and kept from one decomposition to the next (DistributedSimulation::Buffers):
/// a decomposition of the medium body moves ~50 MB of history rows, and
/// zeroing and first-touching fresh buffers for them took most of its time.
struct Bytes {
  ByteBuffer data;
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    put_raw(&value, sizeof(T));
  }
  void put_doubles(const double* values, std::size_t n) { put_raw(values, n * sizeof(double)); }
  void put_raw(const void* bytes, std::size_t n) {
    const std::size_t at = data.size();
    data.resize(at + n);
    std::memcpy(data.data() + at, bytes, n);
  }
};

struct Reader {
  const std::byte* at;
  const std::byte* end;
  template <class T>
  T get() {
    T value;
    std::memcpy(&value, at, sizeof(T));
    at += sizeof(T);
    return value;
  }
  void get_doubles(double* out, std::size_t n) {
    std::memcpy(out, at, n * sizeof(double));
    at += n * sizeof(double);
  }
  [[nodiscard]] bool done() const noexcept { return at >= end; }
};

int as_count(std::size_t n) {
  if (n > std::size_t(std::numeric_limits<int>::max())) throw SolverError("a decomposed run sent more than 2 GB to one process in one exchange");
  return int(n);
}

/// The offsets of blocks of `counts` items laid one after the other (MPI's
/// displacements); returns the items in all.
std::size_t place_one_after_another(const std::vector<int>& counts, std::vector<int>& offsets) {
  std::size_t total = 0;
  for (std::size_t q = 0; q < counts.size(); ++q) {
    offsets[q] = as_count(total);
    total += std::size_t(counts[q]);
  }
  return total;
}

/// Every process sends out[q] to process q; `in` receives what all sent to
/// this one, in rank order (MPI_Alltoallv). `send` is scratch.
void all_to_all(MPI_Comm comm, const std::vector<Bytes>& out, ByteBuffer& send, ByteBuffer& in) {
  const auto ranks = out.size();
  std::vector<int> send_counts(ranks), send_offsets(ranks), receive_counts(ranks), receive_offsets(ranks);
  for (std::size_t q = 0; q < ranks; ++q) send_counts[q] = as_count(out[q].data.size());
  send.resize(place_one_after_another(send_counts, send_offsets));
  for (std::size_t q = 0; q < ranks; ++q)
    if (!out[q].data.empty()) std::memcpy(send.data() + send_offsets[q], out[q].data.data(), out[q].data.size());
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm);
  in.resize(place_one_after_another(receive_counts, receive_offsets));
  MPI_Alltoallv(send.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, in.data(), receive_counts.data(), receive_offsets.data(),
                MPI_BYTE, comm);
}

/// Every process's `mine` one after the other in rank order, on `root` (empty elsewhere; collective).
ByteBuffer gather_bytes(MPI_Comm comm, const Bytes& mine, int root) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const int count = as_count(mine.data.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks)), offsets(static_cast<std::size_t>(ranks));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm);
  const std::size_t total = place_one_after_another(counts, offsets);
  ByteBuffer all(rank == root ? total : 0);
  MPI_Gatherv(mine.data.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, root, comm);
  return all;
}

/// The wall-contact rows of `bytes` ((wall, particle id, facet, row) each) as one archive per wall.
std::vector<HistoryArchive> read_wall_rows(const ByteBuffer& bytes, const std::vector<Wall>& walls) {
  std::vector<HistoryArchive> archives;
  for (const auto& w : walls) archives.emplace_back(w.law.history_size());
  Reader in{bytes.data(), bytes.data() + bytes.size()};
  std::vector<double> row;
  while (!in.done()) {
    const auto w = std::size_t(in.get<std::int64_t>());
    const auto id = in.get<std::int64_t>(), facet = in.get<std::int64_t>();
    row.resize(archives.at(w).stride());
    in.get_doubles(row.data(), row.size());
    archives[w].add({id, facet}, row.data());
  }
  for (auto& a : archives) a.seal();
  return archives;
}

ParticleRecord record_of(const ParticleStore& p, std::size_t i, int owner) {
  return {p.id[i], p.position[i], p.velocity[i], p.angular_velocity[i], p.force[i], p.moment[i], p.radius[i], p.mass[i], p.inertia[i], owner,
          p.material[i]};
}

/// The motion a step changes and the halo update sends (ParticleStore fields).
struct Motion {
  Vec3 position, velocity, angular_velocity, force, moment;
};

}  // namespace

/// The exchange buffers of a decomposition, kept for the next one.
struct DistributedSimulation::Buffers {
  std::vector<Bytes> particles, pairs, walls, requests;
  ByteBuffer send, particle_bytes, pair_bytes, wall_bytes, asked;
  void reset(std::size_t ranks) {
    for (auto* list : {&particles, &pairs, &walls, &requests}) {
      list->resize(ranks);
      for (auto& b : *list) b.data.clear();
    }
  }
};

DistributedSimulation::~DistributedSimulation() = default;

DistributedSimulation::DistributedSimulation(MPI_Comm comm, Simulation& local)
    : comm_(comm), local_(local), buffers_(std::make_unique<Buffers>()) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
  if (local_.periodic_cell()) throw UserError(
        "a periodic cell (the DEM section's \"periodic\" block) cannot be decomposed over processes yet: set participants.dem.mpi_ranks to 1 "
        "and use participants.dem.config.threads for more cores");
  send_slots_.resize(std::size_t(ranks_));
  receive_slots_.resize(std::size_t(ranks_));
  owned_.assign(local_.particles().size(), rank_ == 0 ? 1 : 0);  // until the first decomposition: rank 0's body is the whole
}

void DistributedSimulation::collectively(const std::function<void()>& work) const {
  // 0: done; 1: SolverError; 2: UserError; 3: any other exception.
  int kind = 0;
  std::string message;
  try {
    work();
  } catch (const SolverError& e) {
    kind = 1, message = e.what();
  } catch (const UserError& e) {
    kind = 2, message = e.what();
  } catch (const std::exception& e) {
    kind = 3, message = e.what();
  }
  // The lowest process that failed tells the others what (one of them alone
  // may have seen it: a contact its part holds), and all throw it.
  int failed_rank = kind != 0 ? rank_ : ranks_, first = ranks_;
  MPI_Allreduce(&failed_rank, &first, 1, MPI_INT, MPI_MIN, comm_);
  if (first == ranks_) return;
  int header[2] = {kind, int(message.size())};
  MPI_Bcast(header, 2, MPI_INT, first, comm_);
  message.resize(std::size_t(header[1]));
  MPI_Bcast(message.data(), header[1], MPI_CHAR, first, comm_);
  const std::string text = (rank_ == first ? "" : "process " + std::to_string(first) + ": ") + message;
  if (header[0] == 1) throw SolverError(text);
  if (header[0] == 2) throw UserError(text);
  throw std::runtime_error(text);
}

double DistributedSimulation::critical_timestep() const {
  double mine = local_.particles().size() == 0 ? std::numeric_limits<double>::infinity() : local_.critical_timestep();
  double body = 0.0;
  MPI_Allreduce(&mine, &body, 1, MPI_DOUBLE, MPI_MIN, comm_);
  return body;
}

void DistributedSimulation::step(double dt, ContactRecord record) {
  using clock = std::chrono::steady_clock;
  const auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  if (!decomposed_) {
    first_decomposition(dt);
    rebuild_requested_ = false;
  } else if (rebuild_requested_) {
    rebuild_requested_ = false;
    const auto t = clock::now();
    decompose();
    stats_.decompose_seconds += seconds_since(t);
  }
  auto t = clock::now();
  collectively([&] { local_.step(dt, record); });
  stats_.step_seconds += seconds_since(t);
  t = clock::now();
  update_halo();
  update_wall_forces();
  // The step's own Verlet test saw the halo's wrong motion: the whole body's
  // decides. A rebuild is due at the start of the next step, as on one process
  // (Simulation::step): until then the step's outputs (contacts, damping) stay
  // in the slots they were computed in, for whatever reads them.
  if (lists_used_up()) rebuild_requested_ = true;
  local_.set_lists_stale(false);
  stats_.halo_seconds += seconds_since(t);
}

void DistributedSimulation::first_decomposition(double dt) {
  using clock = std::chrono::steady_clock;
  const auto t = clock::now();
  // A body that will not rebuild at its next step (one already stepped: a
  // prepared sample) or whose next step solves over the whole body (a graded
  // body's seam balance) must be held whole by every process: each takes
  // what must be whole as on one, and then cuts the body where its last
  // rebuild saw it.
  const auto held = std::int64_t(local_.particles().size());
  const int keeps_lists = local_.rebuild_count() > 0 && !local_.lists_stale() ? 1 : 0;
  std::int64_t counts[3] = {-held, held, std::int64_t(keeps_lists || local_.seam_balance_pending())}, body[3] = {0, 0, 0};
  MPI_Allreduce(counts, body, 3, MPI_INT64_T, MPI_MAX, comm_);
  const bool whole_everywhere = -body[0] == body[1];
  if (body[2] != 0 && !whole_everywhere)  // the same decision on every process
    // Not a scenario's error: dem_server builds and steps the model alike on every process.
    throw std::logic_error("a body that has been stepped, or a graded body before its seam balance, is decomposed from the whole body: build (and step) it alike on every process");
  owned_.assign(local_.particles().size(), rank_ == 0 ? 1 : 0);
  if (local_.seam_balance_pending()) {
    // The seam balance (seam_balance.hpp) solves over the whole body: the
    // start of the first step, the rebuild that joins the zones and the
    // balance, is taken on every process as on one.
    collectively([&] { local_.prepare_step(dt); });
  }
  // Lists already built are kept: the parts rebuild where the whole body's
  // last rebuild saw the particles and walls, with its search radius, so
  // with its pairs, grid and canonical order; then everything goes back to
  // where it is. Decomposing at the current positions would be a rebuild the
  // whole body does not take, and other bits.
  std::optional<Simulation::Places> places;
  if (local_.rebuild_count() > 0 && !local_.lists_stale()) places = local_.move_to_references();
  decompose();
  if (places) local_.put_back(*places);
  stats_.decompose_seconds += std::chrono::duration<double>(clock::now() - t).count();
}

bool DistributedSimulation::lists_used_up() const {
  const ParticleStore& p = local_.particles();
  const auto reference = local_.reference_positions();
  // The same |x - x_ref|^2 as the integrator's (integrator.cpp): a max is exact in any order.
  double mine = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (owned_[i]) mine = std::max(mine, norm2(p.position[i] - reference[i]));
  double body = 0.0;
  MPI_Allreduce(&mine, &body, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return local_.verlet_skin_used_up(std::sqrt(body));
}

void DistributedSimulation::update_halo() {
  const ParticleStore& p = local_.particles();
  const auto ranks = std::size_t(ranks_);
  std::vector<std::vector<Motion>> out(ranks), in(ranks);
  std::vector<MPI_Request> requests;
  std::size_t sent = 0;
  for (std::size_t q = 0; q < std::size_t(ranks_); ++q) {
    if (!receive_slots_[q].empty()) {
      in[q].resize(receive_slots_[q].size());
      requests.emplace_back();
      MPI_Irecv(in[q].data(), as_count(in[q].size() * sizeof(Motion)), MPI_BYTE, int(q), 0, comm_, &requests.back());
    }
  }
  for (std::size_t q = 0; q < std::size_t(ranks_); ++q) {
    if (send_slots_[q].empty()) continue;
    for (const std::uint32_t i : send_slots_[q]) out[q].push_back({p.position[i], p.velocity[i], p.angular_velocity[i], p.force[i], p.moment[i]});
    requests.emplace_back();
    MPI_Isend(out[q].data(), as_count(out[q].size() * sizeof(Motion)), MPI_BYTE, int(q), 0, comm_, &requests.back());
    sent += out[q].size() * sizeof(Motion);
  }
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  stats_.halo_bytes_per_step = sent;
  ParticleStore& edit = local_.particle_motion_for_edit();
  for (std::size_t q = 0; q < std::size_t(ranks_); ++q)
    for (std::size_t k = 0; k < receive_slots_[q].size(); ++k) {
      const std::uint32_t i = receive_slots_[q][k];
      const Motion& m = in[q][k];
      edit.position[i] = m.position;
      edit.velocity[i] = m.velocity;
      edit.angular_velocity[i] = m.angular_velocity;
      edit.force[i] = m.force;
      edit.moment[i] = m.moment;
    }
}

void DistributedSimulation::decompose() {
  const ParticleStore& p = local_.particles();
  if (!decomposed_) owned_.assign(p.size(), rank_ == 0 ? 1 : 0);

  // 1. The whole body's extent and largest radius (reductions), and the
  // boxes: kept, or cut anew from every process's owned positions (gathered:
  // the same arrays everywhere, so the same cuts).
  std::vector<double> mine;
  bool unstable = false;
  double r_max = 0.0;
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[3] = {-lo[0], -lo[1], -lo[2]};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!owned_[i]) continue;
    const Vec3& x = p.position[i];
    if (!is_finite(x)) unstable = true;
    mine.insert(mine.end(), {x.x, x.y, x.z});
    r_max = std::max(r_max, p.radius[i]);
    lo[0] = std::min(lo[0], x.x), lo[1] = std::min(lo[1], x.y), lo[2] = std::min(lo[2], x.z);
    hi[0] = std::max(hi[0], x.x), hi[1] = std::max(hi[1], x.y), hi[2] = std::max(hi[2], x.z);
  }
  collectively([&] {
    if (unstable) throw SolverError("a particle position is not finite; the simulation has become unstable");
  });
  double body_r_max = 0.0, body_lo[3], body_hi[3];
  MPI_Allreduce(&r_max, &body_r_max, 1, MPI_DOUBLE, MPI_MAX, comm_);
  MPI_Allreduce(lo, body_lo, 3, MPI_DOUBLE, MPI_MIN, comm_);
  MPI_Allreduce(hi, body_hi, 3, MPI_DOUBLE, MPI_MAX, comm_);
  std::int64_t owned_here = std::int64_t(mine.size() / 3), body_count = 0;
  MPI_Allreduce(&owned_here, &body_count, 1, MPI_INT64_T, MPI_SUM, comm_);
  BodyBounds bounds{{body_lo[0], body_lo[1], body_lo[2]}, {body_hi[0], body_hi[1], body_hi[2]}, std::size_t(body_count)};
  if (body_count == 0) bounds.lo = bounds.hi = Vec3{};  // as the whole body's grid takes an empty body
  local_.set_body_extent(body_r_max, bounds);
  // The boxes: the last decomposition's while they still hold about the same
  // number of particles each (the cuts are then not gathered and computed
  // again: a serial share that grows with the body), new ones where the load
  // has drifted by more than rebalance_tolerance.
  bool recut = !rcb_;
  if (rcb_) {
    std::vector<std::int64_t> load(std::size_t(ranks_), 0), body_load(std::size_t(ranks_), 0);
    for (std::size_t k = 0; k < mine.size() / 3; ++k) ++load[std::size_t(rcb_->owner({mine[3 * k], mine[3 * k + 1], mine[3 * k + 2]}))];
    MPI_Allreduce(load.data(), body_load.data(), ranks_, MPI_INT64_T, MPI_SUM, comm_);
    const double most = double(*std::max_element(body_load.begin(), body_load.end()));
    recut = most > (1.0 + rebalance_tolerance) * double(body_count) / double(ranks_);
  }
  if (recut) {
    const std::vector<double> all = gather_over_processes(mine);
    std::vector<Vec3> points(all.size() / 3);
    for (std::size_t k = 0; k < points.size(); ++k) points[k] = {all[3 * k], all[3 * k + 1], all[3 * k + 2]};
    // Equal weights: the work of a sphere is about that of any other in a
    // packing of one coordination number.
    const std::vector<double> weights(points.size(), 1.0);
    rcb_.emplace(points, weights, ranks_);
    ++stats_.recuts;
  }
  const RcbDecomposition& rcb = *rcb_;
  // A candidate of the next rebuild lies within the reach of its partner:
  // every particle within it of a box is in that box's halo (a relative
  // margin above the round-off of the distance).
  const double halo = local_.next_search_reach() * (1.0 + 1e-9);

  // 2. What goes where: each owned particle to its new owner and to every
  // box whose halo holds it; each history row with an owned particle to the
  // new owners of its two particles, with the partner of a bond that crosses
  // (it stays a pair at any distance); each wall row to its particle's owner.
  const auto ranks = std::size_t(ranks_);
  Buffers& buffers = *buffers_;
  buffers.reset(ranks);
  std::vector<Bytes>& particles_out = buffers.particles;
  std::vector<Bytes>& pairs_out = buffers.pairs;
  std::vector<Bytes>& walls_out = buffers.walls;
  std::vector<int> new_owner(p.size(), -1);
  for (std::size_t i = 0; i < p.size(); ++i) new_owner[i] = rcb.owner(p.position[i]);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!owned_[i]) continue;
    const int dest = new_owner[i];
    const ParticleRecord r = record_of(p, i, dest);
    particles_out[std::size_t(dest)].put(r);
    for (int q = 0; q < ranks_; ++q)
      if (q != dest && rcb.box(q).distance(p.position[i]) < halo) particles_out[std::size_t(q)].put(r);
  }
  const PairContacts& pairs = local_.pair_contacts();
  const bool bonded = local_.settings().particle_law.bonded();
  const std::size_t whole_stride = local_.settings().particle_law.history_size();
  const auto send_row = [&](std::uint32_t a, std::uint32_t b, const double* row) {
    const int na = new_owner[a], nb = new_owner[b];
    const auto put = [&](int q) {
      Bytes& out = pairs_out[std::size_t(q)];
      out.put(p.id[a]);
      out.put(p.id[b]);
      out.put_doubles(row, whole_stride);
    };
    put(na);
    if (nb != na) put(nb);
    if (bonded && na != nb && row[bond_state_column] != 0.0) {
      particles_out[std::size_t(na)].put(record_of(p, b, nb));
      particles_out[std::size_t(nb)].put(record_of(p, a, na));
    }
  };
  if (local_.rebuild_count() == 0) {
    // Not stepped yet: the rows are those seeded (a generated body), rank 0's sent.
    if (const auto& seeded = local_.seeded_pair_history(); seeded && whole_stride != 0) {
      std::unordered_map<std::int64_t, std::uint32_t> slot;
      for (std::size_t i = 0; i < p.size(); ++i) slot[p.id[i]] = std::uint32_t(i);
      for (std::size_t k = 0; k < seeded->size(); ++k) {
        const std::uint32_t a = slot.at(seeded->key(k)[0]), b = slot.at(seeded->key(k)[1]);
        if (owned_[a]) send_row(a, b, seeded->row(k));
      }
    }
  } else if (whole_stride != 0) {
    // A row goes out from the owner of its first particle only: that process
    // holds every pair of the particle (all its partners are in its halo), so
    // every row leaves once and arrives at most once.
    std::vector<double> whole(whole_stride);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const std::uint32_t a = pairs.first[k], b = pairs.second[k];
      if (!owned_[a] || pairs.whole_row_is_zero(k)) continue;
      pairs.copy_whole_row(k, whole.data());
      send_row(a, b, whole.data());
    }
  }
  const auto& walls = local_.walls();
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const WallContacts& wc = local_.wall_contacts(w);
    for (std::size_t k = 0; k < wc.size(); ++k) {
      const std::uint32_t i = wc.particle[k];
      if (!owned_[i] || wc.stride == 0) continue;
      const double* row = wc.history.data() + k * wc.stride;
      if (std::all_of(row, row + wc.stride, [](double v) { return v == 0.0; })) continue;
      Bytes& out = walls_out[std::size_t(new_owner[i])];
      out.put(std::int64_t(w));
      out.put(p.id[i]);
      out.put(std::int64_t(wc.facet[k]));
      out.put_doubles(row, wc.stride);
    }
  }
  std::vector<std::int64_t> kept_ids;  // owned here before and after: the rest migrated
  for (std::size_t i = 0; i < p.size(); ++i)
    if (owned_[i] && new_owner[i] == rank_) kept_ids.push_back(p.id[i]);

  // 3. Exchange, and take the particles (each once: all copies are the same
  // bits) and the rows whose particles are both here.
  all_to_all(comm_, particles_out, buffers.send, buffers.particle_bytes);
  all_to_all(comm_, pairs_out, buffers.send, buffers.pair_bytes);
  all_to_all(comm_, walls_out, buffers.send, buffers.wall_bytes);
  const ByteBuffer& particle_bytes = buffers.particle_bytes;
  const ByteBuffer& pair_bytes = buffers.pair_bytes;
  const ByteBuffer& wall_bytes = buffers.wall_bytes;
  std::vector<ParticleRecord> records(particle_bytes.size() / sizeof(ParticleRecord));
  if (!records.empty()) std::memcpy(records.data(), particle_bytes.data(), records.size() * sizeof(ParticleRecord));
  std::sort(records.begin(), records.end(), [](const ParticleRecord& a, const ParticleRecord& b) { return a.id < b.id; });
  records.erase(std::unique(records.begin(), records.end(), [](const ParticleRecord& a, const ParticleRecord& b) { return a.id == b.id; }),
                records.end());
  ParticleStore store;
  std::vector<std::int64_t> ids;  // in increasing order (the records'), kept when the store moves on
  std::vector<int> owners;        // of ids[k]
  // The owner of a particle here, or -1 if it is not here.
  const auto owner_of = [&ids, &owners](std::int64_t id) {
    const auto found = std::lower_bound(ids.begin(), ids.end(), id);
    return found != ids.end() && *found == id ? owners[std::size_t(found - ids.begin())] : -1;
  };
  for (const ParticleRecord& r : records) {
    ids.push_back(r.id);
    owners.push_back(r.owner);
    append_record(store, r);
  }
  // The rows whose particles are both here (each arrives once, see above);
  // the others are of pairs now apart beyond the reach with no bond, which
  // the rebuild drops as the whole body's does.
  std::vector<HistoryArchive::Key> keys;
  std::vector<double> rows;
  {
    const std::size_t row_bytes = 2 * sizeof(std::int64_t) + whole_stride * sizeof(double);
    const std::size_t count = whole_stride == 0 ? 0 : pair_bytes.size() / row_bytes;
    keys.reserve(count);
    rows.reserve(count * whole_stride);
    for (std::size_t k = 0; k < count; ++k) {
      Reader in{pair_bytes.data() + k * row_bytes, pair_bytes.data() + (k + 1) * row_bytes};
      const auto a = in.get<std::int64_t>(), b = in.get<std::int64_t>();
      if (owner_of(a) < 0 || owner_of(b) < 0) continue;
      keys.push_back({a, b});
      const std::size_t at = rows.size();
      rows.resize(at + whole_stride);
      in.get_doubles(rows.data() + at, whole_stride);
    }
  }
  HistoryArchive pair_archive = HistoryArchive::adopt(whole_stride, std::move(keys), std::move(rows));
  std::vector<HistoryArchive> wall_archives = read_wall_rows(wall_bytes, walls);

  // 4. The new part, its lists, and who sends whose motion after each step.
  local_.replace_body(std::move(store), std::move(pair_archive), std::move(wall_archives));
  collectively([&] { local_.rebuild_if_stale(); });
  const ParticleStore& now = local_.particles();
  owned_.assign(now.size(), 0);
  cell_.resize(now.size());
  {
    // As the grid sorted them (neighbour_search.cpp, CellGrid::cell_of on open axes).
    const double h = local_.cell_size();
    const auto reference = local_.reference_positions();
    for (std::size_t i = 0; i < now.size(); ++i)
      cell_[i] = {std::int64_t(std::floor(reference[i].z / h)), std::int64_t(std::floor(reference[i].y / h)),
                  std::int64_t(std::floor(reference[i].x / h))};
  }
  std::vector<Bytes>& requests = buffers.requests;
  for (auto& s : receive_slots_) s.clear();
  std::size_t owned = 0;
  for (std::size_t i = 0; i < now.size(); ++i) {
    const int owner = owner_of(now.id[i]);
    if (owner == rank_) {
      owned_[i] = 1;
      ++owned;
    } else {
      requests[std::size_t(owner)].put(now.id[i]);
      receive_slots_[std::size_t(owner)].push_back(std::uint32_t(i));
    }
  }
  all_to_all(comm_, requests, buffers.send, buffers.asked);
  const ByteBuffer& asked = buffers.asked;
  // The requests arrive in rank order; each rank's in the order its receive list has them.
  std::vector<std::pair<std::int64_t, std::uint32_t>> slot_of(now.size());
  for (std::size_t i = 0; i < now.size(); ++i) slot_of[i] = {now.id[i], std::uint32_t(i)};
  std::sort(slot_of.begin(), slot_of.end());
  for (auto& s : send_slots_) s.clear();
  {
    std::vector<int> request_counts(ranks);
    std::vector<int> my_counts(ranks);
    for (std::size_t q = 0; q < ranks; ++q) my_counts[q] = as_count(requests[q].data.size() / sizeof(std::int64_t));
    MPI_Alltoall(my_counts.data(), 1, MPI_INT, request_counts.data(), 1, MPI_INT, comm_);
    Reader in{asked.data(), asked.data() + asked.size()};
    for (std::size_t q = 0; q < ranks; ++q)
      for (int k = 0; k < request_counts[q]; ++k) {
        const auto id = in.get<std::int64_t>();
        const auto found = std::lower_bound(slot_of.begin(), slot_of.end(), std::pair<std::int64_t, std::uint32_t>{id, 0});
        if (found == slot_of.end() || found->first != id || !owned_[found->second])
          throw std::logic_error("decomposition: process " + std::to_string(q) + " holds particle " + std::to_string(id) + " as owned here, but it is not");
        send_slots_[q].push_back(found->second);
      }
  }
  std::size_t kept = 0;
  {
    std::sort(kept_ids.begin(), kept_ids.end());
    for (std::size_t i = 0; i < now.size(); ++i)
      if (owned_[i] && std::binary_search(kept_ids.begin(), kept_ids.end(), now.id[i])) ++kept;
  }
  stats_.owned = owned;
  stats_.halo = now.size() - owned;
  stats_.migrated = decomposed_ ? owned - kept : 0;
  ++stats_.decompositions;
  decomposed_ = true;
}

namespace {
/// One wall contact of an owned particle as it travels: its place in the
/// whole body's contact order (wall, then particle slot: cell and id, then facet) and its terms.
struct WallTerm {
  std::uint32_t wall = 0, facet = 0;
  std::array<std::int64_t, 3> cell{};
  std::int64_t id = 0;
  std::array<double, 3> weights{};
  Vec3 force, point, couple;
};
static_assert(std::is_trivially_copyable_v<WallTerm>);
}  // namespace

void DistributedSimulation::update_wall_forces() {
  const auto& walls = local_.walls();
  if (walls.empty()) return;
  const ParticleStore& p = local_.particles();
  const ContactOutputs& out = local_.outputs_with_wall_contacts();
  const bool with_couple = !out.couple.empty();
  std::vector<WallTerm> mine;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const WallContacts& contacts = local_.wall_contacts(w);
    const std::size_t offset = local_.wall_output_offset(w);
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const std::uint32_t i = contacts.particle[k];
      const std::size_t o = offset + k;
      // add_wall_contact skips a contact without load: none travels.
      if (!owned_[i] || (out.force[o] == Vec3{} && (!with_couple || out.couple[o] == Vec3{}))) continue;
      mine.push_back({std::uint32_t(w), contacts.facet[k], cell_[i], p.id[i], contacts.weights[k], out.force[o], out.point[o],
                      with_couple ? out.couple[o] : Vec3{}});
    }
  }
  const int count = as_count(mine.size() * sizeof(WallTerm));
  std::vector<int> counts(static_cast<std::size_t>(ranks_)), offsets(static_cast<std::size_t>(ranks_));
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  const std::size_t total = place_one_after_another(counts, offsets);
  std::vector<WallTerm> all(total / sizeof(WallTerm));
  MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, comm_);
  const auto place = [](const WallTerm& t) { return std::tie(t.wall, t.cell, t.id, t.facet); };
  std::sort(all.begin(), all.end(), [&](const WallTerm& a, const WallTerm& b) { return place(a) < place(b); });
  for (std::size_t w = 0; w < walls.size(); ++w) clear_wall_forces(local_.wall_results_for_edit(w));
  for (const WallTerm& t : all)
    add_wall_contact(local_.wall_results_for_edit(t.wall), t.facet, t.weights, t.force, t.point, with_couple ? &t.couple : nullptr);
}

void DistributedSimulation::save_whole_body(StateWriter& out) {
  if (!decomposed_) {  // never cut: rank 0 holds the whole body
    if (rank_ == 0) local_.save_state(out);
    return;
  }
  // 1. Every process's own particles, each with its reference position (of
  // the last rebuild, the whole body's), the history rows of their pairs
  // (each by the owner of its first particle) and of their wall contacts.
  const ParticleStore& p = local_.particles();
  const auto reference = local_.reference_positions();
  Bytes particles, pairs, walls;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (owned_[i]) {
      particles.put(record_of(p, i, rank_));
      particles.put(reference[i]);
    }
  const PairContacts& list = local_.pair_contacts();
  const std::size_t whole_stride = local_.settings().particle_law.history_size();
  std::vector<double> whole(whole_stride);
  if (whole_stride != 0)
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (!owned_[list.first[k]] || list.whole_row_is_zero(k)) continue;
      list.copy_whole_row(k, whole.data());
      pairs.put(p.id[list.first[k]]);
      pairs.put(p.id[list.second[k]]);
      pairs.put_doubles(whole.data(), whole_stride);
    }
  for (std::size_t w = 0; w < local_.walls().size(); ++w) {
    const WallContacts& wc = local_.wall_contacts(w);
    for (std::size_t k = 0; k < wc.size(); ++k) {
      const double* row = wc.history.data() + k * wc.stride;
      if (!owned_[wc.particle[k]] || wc.stride == 0 || std::all_of(row, row + wc.stride, [](double v) { return v == 0.0; })) continue;
      walls.put(std::int64_t(w));
      walls.put(p.id[wc.particle[k]]);
      walls.put(std::int64_t(wc.facet[k]));
      walls.put_doubles(row, wc.stride);
    }
  }
  const ByteBuffer all_particles = gather_bytes(comm_, particles, 0), all_pairs = gather_bytes(comm_, pairs, 0), all_walls = gather_bytes(comm_, walls, 0);
  if (rank_ != 0) return;

  // 2. The whole body at its references, and where it is now.
  struct Gathered {
    ParticleRecord record;
    Vec3 reference;
  };
  std::vector<Gathered> body(all_particles.size() / sizeof(Gathered));
  if (!body.empty()) std::memcpy(body.data(), all_particles.data(), all_particles.size());
  std::sort(body.begin(), body.end(), [](const Gathered& a, const Gathered& b) { return a.record.id < b.record.id; });
  ParticleStore at_reference;
  Simulation::Places now = local_.places();
  now.id.clear();
  now.position.clear();
  for (const Gathered& g : body) {
    const ParticleRecord& r = g.record;
    append_record(at_reference, r);
    at_reference.position.back() = g.reference;
    now.id.push_back(r.id);
    now.position.push_back(r.position);
  }
  std::vector<HistoryArchive::Key> keys;
  std::vector<double> rows;
  {
    const std::size_t row_bytes = 2 * sizeof(std::int64_t) + whole_stride * sizeof(double);
    const std::size_t count = whole_stride == 0 ? 0 : all_pairs.size() / row_bytes;
    rows.resize(count * whole_stride);
    for (std::size_t k = 0; k < count; ++k) {
      Reader in{all_pairs.data() + k * row_bytes, all_pairs.data() + (k + 1) * row_bytes};
      const auto a = in.get<std::int64_t>(), b = in.get<std::int64_t>();
      keys.push_back({a, b});
      in.get_doubles(rows.data() + k * whole_stride, whole_stride);
    }
  }
  std::vector<HistoryArchive> wall_archives = read_wall_rows(all_walls, local_.walls());

  // 3. Rank 0's part becomes the whole body for the write (its lists made
  // where the whole body's last rebuild made them), then goes back.
  StateWriter part;
  local_.save_state(part);
  const std::string part_bytes = part.take();
  local_.replace_body_at_references(std::move(at_reference), HistoryArchive::adopt(whole_stride, std::move(keys), std::move(rows)),
                                    std::move(wall_archives), now, local_.rebuild_count());
  local_.save_state(out);
  StateReader back(part_bytes, "this process's part of the body");
  local_.load_state(back);
}

std::vector<ParticleRecord> DistributedSimulation::gather_particles(int root) const {
  const ParticleStore& p = local_.particles();
  Bytes mine;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (owned_.empty() ? rank_ == 0 : owned_[i] != 0) mine.put(record_of(p, i, rank_));
  const ByteBuffer all = gather_bytes(comm_, mine, root);
  std::vector<ParticleRecord> out(all.size() / sizeof(ParticleRecord));
  if (!out.empty()) std::memcpy(out.data(), all.data(), all.size());
  std::sort(out.begin(), out.end(), [](const ParticleRecord& a, const ParticleRecord& b) { return a.id < b.id; });
  return out;
}

std::vector<double> DistributedSimulation::gather_on_root(std::span<const double> values, int root) const {
  const int mine = as_count(values.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks_)), offsets(static_cast<std::size_t>(ranks_));
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_);
  const std::size_t total = place_one_after_another(counts, offsets);
  std::vector<double> all(rank_ == root ? total : 0);
  MPI_Gatherv(values.data(), mine, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, root, comm_);
  return all;
}

std::vector<double> DistributedSimulation::gather_over_processes(std::span<const double> values) const {
  const int mine = as_count(values.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks_)), offsets(static_cast<std::size_t>(ranks_));
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  const std::size_t total = place_one_after_another(counts, offsets);
  std::vector<double> all(total);
  MPI_Allgatherv(values.data(), mine, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, comm_);
  return all;
}

void DistributedSimulation::sum_over_processes(std::span<ExactSum> sums) const {
  // The limbs of exact sums add (exact_sum.hpp): an integer MPI_SUM of them is the exact total.
  constexpr std::size_t width = std::tuple_size_v<decltype(ExactSum{}.normalised_limbs())>;
  std::vector<std::int64_t> limbs(sums.size() * width), total(sums.size() * width);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    const auto l = sums[k].normalised_limbs();
    std::copy(l.begin(), l.end(), limbs.begin() + std::ptrdiff_t(k * width));
  }
  MPI_Allreduce(limbs.data(), total.data(), as_count(limbs.size()), MPI_INT64_T, MPI_SUM, comm_);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    std::array<std::int64_t, width> l{};
    std::copy_n(total.begin() + std::ptrdiff_t(k * width), width, l.begin());
    sums[k] = ExactSum::from_limbs(l);
  }
}

Measurements DistributedSimulation::measure() const {
  MeasureSums sums = measure_sums(local_, owned_);
  sum_over_processes(sums.sums);
  std::int64_t counts[3] = {sums.particles, sums.pair_contacts, sums.wall_contacts}, total[3]{};
  MPI_Allreduce(counts, total, 3, MPI_INT64_T, MPI_SUM, comm_);
  int complete = sums.outputs_complete ? 1 : 0, all_complete = 0;
  MPI_Allreduce(&complete, &all_complete, 1, MPI_INT, MPI_MIN, comm_);
  sums.particles = total[0];
  sums.pair_contacts = total[1];
  sums.wall_contacts = total[2];
  sums.outputs_complete = all_complete != 0;
  return measurements_from(sums);
}

Vec3 DistributedSimulation::momentum() const {
  const ParticleStore& p = local_.particles();
  auto body = exact_accumulators<3>(p.size(), local_.threads(), [&](std::size_t i) {
    if (!owned_[i]) return std::array<double, 3>{};
    const Vec3 m = p.mass[i] * p.velocity[i];
    return std::array<double, 3>{m.x, m.y, m.z};
  });
  sum_over_processes(body);
  return {body[0].value(), body[1].value(), body[2].value()};
}

BondCounts DistributedSimulation::bond_counts() const {
  const PairContacts& pairs = local_.pair_contacts();
  std::int64_t mine[4] = {0, 0, 0, 0}, body[4] = {0, 0, 0, 0};
  if (local_.settings().particle_law.bonded() && pairs.stride != 0)
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      if (!owned_[pairs.first[k]]) continue;
      switch (bond_state(pairs.row(k))) {
        case BondState::intact: ++mine[0]; break;
        case BondState::damaged: ++mine[1]; break;
        case BondState::broken_tension: ++mine[2]; break;
        case BondState::broken_shear: ++mine[3]; break;
        case BondState::none: break;
      }
    }
  MPI_Allreduce(mine, body, 4, MPI_INT64_T, MPI_SUM, comm_);
  BondCounts c;
  c.intact = body[0];
  c.damaged = body[1];
  c.broken_tension = body[2];
  c.broken_shear = body[3];
  return c;
}

void append_record(ParticleStore& store, const ParticleRecord& r) {
  store.id.push_back(r.id);
  store.position.push_back(r.position);
  store.velocity.push_back(r.velocity);
  store.angular_velocity.push_back(r.angular_velocity);
  store.force.push_back(r.force);
  store.moment.push_back(r.moment);
  store.radius.push_back(r.radius);
  store.mass.push_back(r.mass);
  store.inertia.push_back(r.inertia);
  store.material.push_back(r.material);
}

}  // namespace dfc::dem
