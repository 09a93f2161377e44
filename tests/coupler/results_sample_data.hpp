#pragma once
// Small, deterministic particle and grid snapshots and a time-series row
// generator, shared by the results tests and the sample-file program the
// tool tests run on.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <unistd.h>
#include <vector>

#include "dfc/protocol/array.hpp"

namespace dfc::coupler::testing {

// Built by hand rather than with Array::from_f64 so the results tests depend
// only on the Array struct, not on the protocol codec.
template <class T>
protocol::Array make_array(std::string name, protocol::DType dtype, std::vector<std::int64_t> shape, const std::vector<T>& values) {
  protocol::Array array;
  array.name = std::move(name);
  array.dtype = dtype;
  array.shape = std::move(shape);
  array.bytes.resize(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(array.bytes.data(), values.data(), array.bytes.size());
  return array;
}

inline protocol::Array f64_array(std::string name, std::vector<std::int64_t> shape, const std::vector<double>& values) {
  return make_array(std::move(name), protocol::DType::f64, std::move(shape), values);
}

inline protocol::Array i64_array(std::string name, std::vector<std::int64_t> shape, const std::vector<std::int64_t>& values) {
  return make_array(std::move(name), protocol::DType::i64, std::move(shape), values);
}

/// `n` particles on a line, moving with the snapshot index `k`.
inline std::vector<protocol::Array> particle_arrays(std::int64_t n, int k) {
  std::vector<double> position, velocity, radius;
  std::vector<std::int64_t> id;
  for (std::int64_t i = 0; i < n; ++i) {
    const double x = 0.01 * static_cast<double>(i);
    position.insert(position.end(), {x, 0.001 * k, std::sin(x)});
    velocity.insert(velocity.end(), {0.0, 0.1 * k, -1.0});
    radius.push_back(0.002 + 1e-4 * static_cast<double>(i % 3));
    id.push_back((std::int64_t{1} << 53) + 1 + i);  // not representable as double: catches a lossy round trip
  }
  return {f64_array("particle_position", {n, 3}, position), f64_array("particle_radius", {n}, radius),
          f64_array("particle_velocity", {n, 3}, velocity), i64_array("particle_id", {n}, id),
          f64_array("wall_force", {2, 3}, {1, 2, 3, 4, 5, 6})};  // leading dimension is not n: not an XDMF attribute
}

/// A structured block of nx × ny × nz hexahedral zones, displaced by snapshot index `k`.
inline std::vector<protocol::Array> grid_arrays(int nx, int ny, int nz, int k) {
  const auto node = [&](int i, int j, int l) -> std::int64_t { return (static_cast<std::int64_t>(l) * (ny + 1) + j) * (nx + 1) + i; };
  std::vector<double> position, displacement, velocity, stress;
  for (int l = 0; l <= nz; ++l)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        position.insert(position.end(), {1.0 * i, 1.0 * j, 1.0 * l});
        displacement.insert(displacement.end(), {0.0, 0.0, -0.01 * k * l});
        velocity.insert(velocity.end(), {0.0, 0.0, -0.1 * l});
      }
  std::vector<std::int64_t> zones;
  for (int l = 0; l < nz; ++l)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        // VTK hexahedron order: bottom face counter-clockwise, then the top face.
        zones.insert(zones.end(), {node(i, j, l), node(i + 1, j, l), node(i + 1, j + 1, l), node(i, j + 1, l), node(i, j, l + 1),
                                   node(i + 1, j, l + 1), node(i + 1, j + 1, l + 1), node(i, j + 1, l + 1)});
        stress.insert(stress.end(), {-1e5 * (l + 1), 0.0, 0.0, -1e5 * (l + 1), 0.0, -2e5 * (l + 1)});
      }
  const std::int64_t nodes = static_cast<std::int64_t>(nx + 1) * (ny + 1) * (nz + 1);
  const std::int64_t cells = static_cast<std::int64_t>(nx) * ny * nz;
  return {f64_array("node_position", {nodes, 3}, position), f64_array("node_displacement", {nodes, 3}, displacement),
          f64_array("node_velocity", {nodes, 3}, velocity), i64_array("zone_nodes", {cells, 8}, zones),
          f64_array("zone_stress", {cells, 6}, stress)};
}

/// Columns of a pile-driving run, in the names the plot tool looks for.
inline std::vector<std::string> sample_columns() {
  return {"step",
          "time_s",
          "pile_displacement_m",
          "pile_force_n",
          "interface_force_dem_x",
          "interface_force_dem_y",
          "interface_force_dem_z",
          "interface_force_continuum_x",
          "interface_force_continuum_y",
          "interface_force_continuum_z",
          "ufr_dem",
          "ufr_continuum"};
}

inline std::map<std::string, std::string> sample_units() {
  return {{"time_s", "s"}, {"pile_displacement_m", "m"}, {"pile_force_n", "N"}};
}

inline std::vector<double> sample_row(int i) {
  const double t = 1e-3 * i;
  const double f = 1e3 * (1.0 - std::exp(-0.05 * i));
  return {static_cast<double>(i), t, 2e-4 * i, f, 0.1 * f, -0.1 * f, -f, -0.1 * f, 0.1 * f, f, std::exp(-0.1 * i), 0.5 * std::exp(-0.08 * i)};
}

/// A fresh, empty directory under the system temporary directory, removed on destruction.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag)
      : path_(std::filesystem::temp_directory_path() / ("dfc-results-" + tag + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace dfc::coupler::testing
