// dem_server --mpi (mpi_server.hpp): rank 0 serves the protocol and sends
// each request on to the other processes, which run it on their backends.
#include "dfc/dem/mpi_server.hpp"

#include <cstdint>
#include <exception>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/common/state_archive.hpp"

namespace dfc::dem {

namespace {

/// What rank 0 sends the others before a backend call (the call's inputs follow as bytes).
enum class Command : std::int32_t { configure, set_interface, advance, monitors, snapshot, checkpoint, restore, stop };

/// Sends `command` and its inputs from rank 0 to every process (collective).
void broadcast(MPI_Comm comm, Command command, const std::string& bytes) {
  if (bytes.size() > std::size_t(std::numeric_limits<int>::max())) throw std::length_error("a request over 2 GiB cannot be sent to the other processes");
  std::int32_t header[2] = {std::int32_t(command), std::int32_t(bytes.size())};
  MPI_Bcast(header, 2, MPI_INT32_T, 0, comm);
  if (!bytes.empty()) MPI_Bcast(const_cast<char*>(bytes.data()), header[1], MPI_CHAR, 0, comm);
}

/// On a process other than 0: the next command and its inputs.
Command receive(MPI_Comm comm, std::string& bytes) {
  std::int32_t header[2] = {0, 0};
  MPI_Bcast(header, 2, MPI_INT32_T, 0, comm);
  bytes.assign(std::size_t(header[1]), '\0');
  if (header[1] > 0) MPI_Bcast(bytes.data(), header[1], MPI_CHAR, 0, comm);
  return Command(header[0]);
}

void write_arrays(StateWriter& out, const std::vector<protocol::Array>& arrays) {
  out.value(std::uint64_t(arrays.size()));
  for (const protocol::Array& a : arrays) {
    out.string(a.name);
    out.value(a.dtype);
    out.vector(a.shape);
    out.vector(a.bytes);
  }
}

std::vector<protocol::Array> read_arrays(StateReader& in) {
  std::vector<protocol::Array> arrays(std::size_t(in.value<std::uint64_t>()));
  for (protocol::Array& a : arrays) {
    a.name = in.string();
    in.value(a.dtype);
    in.vector(a.shape);
    in.vector(a.bytes);
  }
  return arrays;
}

std::string encode(const protocol::InterfaceMesh& mesh) {
  StateWriter out;
  out.vector(mesh.node_ids);
  out.vector(mesh.coordinates);
  out.vector(mesh.facets);
  return out.take();
}

protocol::InterfaceMesh decode_mesh(std::string_view bytes) {
  StateReader in(bytes, "the interface mesh rank 0 sent");
  protocol::InterfaceMesh mesh;
  in.vector(mesh.node_ids);
  in.vector(mesh.coordinates);
  in.vector(mesh.facets);
  in.finish();
  return mesh;
}

std::string encode(const protocol::AdvanceRequest& request) {
  StateWriter out;
  out.value(request.first_step);
  out.value(request.n_steps);
  out.value(request.dt);
  write_arrays(out, request.inputs);
  return out.take();
}

protocol::AdvanceRequest decode_advance(std::string_view bytes) {
  StateReader in(bytes, "the advance rank 0 sent");
  protocol::AdvanceRequest request;
  in.value(request.first_step);
  in.value(request.n_steps);
  in.value(request.dt);
  request.inputs = read_arrays(in);
  in.finish();
  return request;
}

/// Rank 0's backend: each call is sent to the other processes, then run here.
class ReplicatedBackend final : public protocol::SolverBackend {
 public:
  ReplicatedBackend(MPI_Comm comm, std::unique_ptr<protocol::SolverBackend> inner, bool& stopped)
      : comm_(comm), inner_(std::move(inner)), stopped_(stopped) {}

  [[nodiscard]] protocol::SolverIdentity identity() const override { return inner_->identity(); }
  nlohmann::json configure(const nlohmann::json& section) override {
    broadcast(comm_, Command::configure, section.dump());
    return inner_->configure(section);
  }
  void set_interface(const protocol::InterfaceMesh& mesh) override {
    broadcast(comm_, Command::set_interface, encode(mesh));
    inner_->set_interface(mesh);
  }
  protocol::AdvanceResult advance(const protocol::AdvanceRequest& request) override {
    broadcast(comm_, Command::advance, encode(request));
    return inner_->advance(request);
  }
  [[nodiscard]] nlohmann::json monitors() override {
    broadcast(comm_, Command::monitors, {});
    return inner_->monitors();
  }
  [[nodiscard]] std::vector<protocol::Array> snapshot(std::string& kind) override {
    broadcast(comm_, Command::snapshot, {});
    return inner_->snapshot(kind);
  }
  [[nodiscard]] std::string checkpoint_state() override {
    broadcast(comm_, Command::checkpoint, {});
    return inner_->checkpoint_state();
  }
  void restore_state(std::string_view bytes) override {
    broadcast(comm_, Command::restore, std::string(bytes));
    inner_->restore_state(bytes);
  }

  ~ReplicatedBackend() override {
    if (stopped_) return;
    stopped_ = true;
    broadcast(comm_, Command::stop, {});
  }
  ReplicatedBackend(const ReplicatedBackend&) = delete;
  ReplicatedBackend& operator=(const ReplicatedBackend&) = delete;

 private:
  MPI_Comm comm_;
  std::unique_ptr<protocol::SolverBackend> inner_;
  bool& stopped_;  ///< whether "stop" was sent (once, by this backend or by run_mpi_server_main)
};

/// A process other than 0: runs rank 0's requests on `backend` until "stop".
/// A request that fails here failed on rank 0 too, which reports it.
void follow(MPI_Comm comm, protocol::SolverBackend& backend) {
  std::string bytes;
  for (;;) {
    const Command command = receive(comm, bytes);
    if (command == Command::stop) return;
    try {
      std::string kind;
      switch (command) {
        case Command::configure: (void)backend.configure(nlohmann::json::parse(bytes)); break;
        case Command::set_interface: backend.set_interface(decode_mesh(bytes)); break;
        case Command::advance: (void)backend.advance(decode_advance(bytes)); break;
        case Command::monitors: (void)backend.monitors(); break;
        case Command::snapshot: (void)backend.snapshot(kind); break;
        case Command::checkpoint: (void)backend.checkpoint_state(); break;
        case Command::restore: backend.restore_state(bytes); break;
        case Command::stop: return;
      }
    } catch (const std::exception&) {  // NOLINT(bugprone-empty-catch): rank 0 met the same error and replies with it
    }
  }
}

}  // namespace

int run_mpi_server_main(int argc, char** argv, const protocol::ServerProgram& program, const RankBackendFactory& make_backend) {
  int provided = 0;
  // OpenMP threads inside a process never call MPI: the main thread alone does (FUNNELED).
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, processes = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &processes);
  int status = 0;
  if (rank == 0) {
    std::vector<char*> args;
    for (int i = 0; i < argc; ++i)
      if (std::string_view(argv[i]) != "--mpi") args.push_back(argv[i]);
    bool stopped = false;
    protocol::ServerProgram served = program;
    served.make_backend = [&] { return std::make_unique<ReplicatedBackend>(MPI_COMM_WORLD, make_backend(processes, 0), stopped); };
    status = protocol::run_server_main(int(args.size()), args.data(), served);
    if (status != 0 && processes > 1) {
      // The others may wait in a collective rank 0 never reaches: end them all.
      std::cerr << program.name << ": rank 0 ends with status " << status << "; aborting the other " << processes - 1 << " processes" << std::endl;
      MPI_Abort(MPI_COMM_WORLD, status);
    }
    if (!stopped) broadcast(MPI_COMM_WORLD, Command::stop, {});  // --help, --version: no backend was made
  } else {
    try {
      const auto backend = make_backend(processes, rank);
      follow(MPI_COMM_WORLD, *backend);
    } catch (const std::exception& e) {
      std::cerr << program.name << ": process " << rank << ": " << e.what() << std::endl;
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
  }
  MPI_Finalize();
  return status;
}

}  // namespace dfc::dem
