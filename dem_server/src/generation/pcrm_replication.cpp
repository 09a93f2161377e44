#include "dfc/dem/pcrm_replication.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "dfc/common/errors.hpp"
#include "dfc/common/work_progress.hpp"
#include "dfc/dem/region_config.hpp"

namespace dfc::dem {


double clearance(const GeneratedSphere& s, const BedRegion& r) noexcept {
  const Vec3& x = s.centre;
  double d = 0.0;
  if (r.shape == BedRegion::Shape::box) {
    d = std::min({x.x - r.min.x, r.max.x - x.x, x.y - r.min.y, r.max.y - x.y, x.z - r.min.z, r.max.z - x.z});
  } else {
    d = std::min({r.radius - std::hypot(x.x - r.axis_x, x.y - r.axis_y), x.z - r.z_min, r.z_max - x.z});
  }
  return d - s.radius;
}

HistoryArchive ReplicatedBody::archive() const {
  HistoryArchive out(stride);
  out.reserve(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) out.add({id[pairs[k][0]], id[pairs[k][1]]}, rows.data() + k * stride);
  out.seal();
  return out;
}

HistoryArchive ReplicatedBody::release_into_archive() {
  std::vector<HistoryArchive::Key> keys(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) keys[k] = {id[pairs[k][0]], id[pairs[k][1]]};
  const auto release = [](auto& v) { std::remove_reference_t<decltype(v)>().swap(v); };
  release(id);
  release(spheres);
  release(material);
  release(pairs);
  return HistoryArchive::adopt(stride, std::move(keys), std::exchange(rows, {}));
}

ReplicatedBody replicate(const PreparedRev& rev, const BedRegion& region, double protrusion_fraction, bool periodic) {
  const auto [lo, hi] = region_bounds(region);
  return replicate(rev, lo, hi, [&](const GeneratedSphere& s) { return clearance(s, region) >= -protrusion_fraction * s.radius; }, periodic);
}

std::array<int, 3> copies_to_cover(const Vec3& cell_length, const Vec3& lo, const Vec3& hi) {
  const double extent[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  const double edge[3] = {cell_length.x, cell_length.y, cell_length.z};
  std::array<int, 3> copies{};
  // An extent of a whole number of edges, (lo + k l) - lo, is k l only to
  // round-off: one more copy there would tile a periodic body wrongly (its
  // pairs across the faces wrap to the trimmed copy). 1e-9 of an edge is far
  // below any sphere, so a part of a copy that thin holds none.
  for (std::size_t a = 0; a < 3; ++a) copies[a] = std::max(1, int(std::ceil(extent[a] / edge[a] * (1.0 - 1e-9))));
  return copies;
}

void reserve_room(ReplicatedBody& body, std::size_t spheres, std::size_t pairs) {
  body.id.reserve(body.id.size() + spheres);
  body.spheres.reserve(body.spheres.size() + spheres);
  body.material.reserve(body.material.size() + spheres);
  body.pairs.reserve(body.pairs.size() + pairs);
  body.rows.reserve(body.rows.size() + pairs * body.stride);
}

ReplicatedBody replicate(const PreparedRev& rev, const Vec3& lo, const Vec3& hi, const std::function<bool(const GeneratedSphere&)>& keep,
                         bool periodic) {
  ReplicatedBody body;
  body.stride = rev.stride;
  body.copies = replicate_into(body, rev, lo, hi, keep, 0, 0, periodic);
  return body;
}

std::array<int, 3> replicate_into(ReplicatedBody& body, const PreparedRev& rev, const Vec3& lo, const Vec3& hi,
                                  const std::function<bool(const GeneratedSphere&)>& keep, std::uint16_t material, std::int64_t id_offset,
                                  bool periodic) {
  if (body.stride != rev.stride) throw std::logic_error("replicate_into: the body's history stride is not the REV's");
  const Vec3 l = rev.cell.length();
  const std::array<int, 3> part_copies = copies_to_cover(l, lo, hi);
  const auto [nx, ny, nz] = part_copies;
  const std::int64_t copies = std::int64_t(nx) * ny * nz;
  const std::int64_t n = std::int64_t(rev.spheres.size());
  if (double(body.spheres.size()) + double(copies) * double(n) > double(std::numeric_limits<std::uint32_t>::max()))
    throw UserError("replicating the REV " + std::to_string(copies) + " times gives more spheres than one DEM model can hold; use a smaller region or a larger scale factor");
  // Every copy of every sphere and pair at most: appending then never copies the arrays.
  reserve_room(body, std::size_t(copies * n), std::size_t(copies) * rev.pairs.size());

  // Slot of (sphere i, copy c) in the body, or -1 if trimmed; copy index c = (cz ny + cy) nx + cx.
  std::vector<std::int64_t> slot(std::size_t(copies * n), -1);
  for (std::int64_t c = 0; c < copies; ++c) {
    work_progress::advance();  // a copy of the REV: a large body is thousands of them
    const Vec3 origin{lo.x + double(c % nx) * l.x, lo.y + double((c / nx) % ny) * l.y, lo.z + double(c / (std::int64_t(nx) * ny)) * l.z};
    for (std::int64_t i = 0; i < n; ++i) {
      const GeneratedSphere& s = rev.spheres[std::size_t(i)];
      const GeneratedSphere placed{origin + (s.centre - rev.cell.lo), s.radius};
      if (!keep(placed)) continue;
      slot[std::size_t(i * copies + c)] = std::int64_t(body.spheres.size());
      body.spheres.push_back(placed);
      body.id.push_back(i * copies + c + id_offset);
      body.material.push_back(material);
    }
  }
  // Pairs: first of copy c with second of copy c + image, where that copy exists.
  for (std::size_t k = 0; k < rev.pairs.size(); ++k) {
    work_progress::advance_every(std::int64_t(k), 1024);  // each REV pair is placed in every copy
    const RevPair& p = rev.pairs[k];
    for (std::int64_t c = 0; c < copies; ++c) {
      std::int64_t cx = c % nx + p.image[0], cy = (c / nx) % ny + p.image[1], cz = c / (std::int64_t(nx) * ny) + p.image[2];
      if (periodic) {  // the copies tile a periodic cell: the last copy's neighbour is the first
        cx = (cx + nx) % nx;
        cy = (cy + ny) % ny;
        cz = (cz + nz) % nz;
      }
      if (cx < 0 || cy < 0 || cz < 0 || cx >= nx || cy >= ny || cz >= nz) continue;
      const std::int64_t partner = (cz * ny + cy) * nx + cx;
      const std::int64_t a = slot[std::size_t(std::int64_t(p.first) * copies + c)];
      const std::int64_t b = slot[std::size_t(std::int64_t(p.second) * copies + partner)];
      if (a < 0 || b < 0) continue;
      body.pairs.push_back({std::uint32_t(a), std::uint32_t(b)});
      body.rows.insert(body.rows.end(), rev.rows.begin() + std::ptrdiff_t(k * rev.stride), rev.rows.begin() + std::ptrdiff_t((k + 1) * rev.stride));
    }
  }
  return part_copies;
}

}  // namespace dfc::dem
