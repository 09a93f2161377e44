#pragma once
// XDMF sidecar: the XML that lets ParaView (Xdmf or Xdmf3 reader) open the
// particle and grid snapshots of a results file directly. The heavy data stay
// in the HDF5 file; the XDMF only describes them, referring to datasets as
// "<file>.h5:/snapshots/<role>/<index>/<array>" relative to the sidecar.
//
// One temporal collection per role, named for what it holds ("dem_particles",
// "continuum_grid"). A "particles" snapshot becomes a
// Polyvertex grid on particle_position (its connectivity 0..n-1 is a dataset
// of the results file, polyvertex_connectivity_path(n): the Xdmf3 reader makes
// no cells from a Polyvertex topology without one); a "grid" snapshot a Hexahedron grid
// with Geometry node_position and Topology zone_nodes (VTK hexahedron order,
// which is also XDMF's). Arrays whose leading dimension is the point count
// become node attributes, the zone count cell attributes, with Scalar /
// Vector / Tensor6 / Tensor chosen from the trailing dimension (1, 3, 6, 9);
// anything else is left out. Snapshots of other kinds, or without geometry,
// or with no points, are left out. Attribute names carry their unit where
// the dataset's name does not (particle_radius -> particle_radius_m, ...).
//
// A particle snapshot's bonds (bond_particle_index [m,2], rows of
// particle_position: dem_server/include/dfc/dem/snapshot_pairs.hpp) form a
// second collection "<role>_bonds" of Polyline cells of two nodes, with every
// bond_* array of m values as a cell attribute; from a server that sends only
// bond_position and bond_state, points at the midpoints. Its walls and pile
// (wall_vertices, wall_facets) form a third, "<role>_walls", of triangles
// with wall_facet_wall shown as "wall_index"; where the wall names of the
// role are known, the collection's Information "wall_index" lists them
// ("0 floor; 1 pile; 2 coupling surface": ParaView does not show it, a
// reader of the file does).
//
// Tensor6 components in XDMF are ordered xx, xy, xz, yy, yz, zz; zone_stress
// must be written in that order for ParaView's component names to be right.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dfc/protocol/array.hpp"

namespace dfc::coupler {

/// What the XDMF needs to know of one stored array (not its values).
struct XdmfArrayInfo {
  std::string name;
  protocol::DType dtype = protocol::DType::f64;
  std::vector<std::int64_t> shape;
};

/// One stored snapshot: where it lives in the HDF5 file and what it holds.
struct XdmfSnapshot {
  std::string role;
  std::string group_path;  ///< absolute HDF5 path of the snapshot group, e.g. "/snapshots/dem/000003"
  std::int64_t step = 0;
  double time = 0.0;
  std::string kind;  ///< "particles" or "grid"; other kinds are not described
  std::vector<XdmfArrayInfo> arrays;
};

/// The point count when `snapshot` is drawn as vertices (particles, or a grid
/// without hexahedra); nothing when it is drawn otherwise or left out.
[[nodiscard]] std::optional<std::int64_t> polyvertex_point_count(const XdmfSnapshot& snapshot);
/// The bond count when `snapshot` (particles) carries bond_position [m, 3] and
/// bond_state [m] but no bond_particle_index (an older server): the sidecar
/// then draws them as points at the bond midpoints with their state, which
/// need a Polyvertex connectivity of m. Nothing when the bonds are drawn as lines.
[[nodiscard]] std::optional<std::int64_t> bond_point_count(const XdmfSnapshot& snapshot);
/// Where the results file holds 0, 1, ..., points-1 (int64) for Polyvertex topologies: "/xdmf/polyvertex_<points>".
[[nodiscard]] std::string polyvertex_connectivity_path(std::int64_t points);

/// Per role, the name of each wall in the order of wall_facet_wall's index.
using WallNames = std::map<std::string, std::vector<std::string>>;

/// The XDMF document for `snapshots`, referring to the HDF5 file by `h5_file_name`
/// (a path relative to the sidecar, normally just the file name).
[[nodiscard]] std::string xdmf_document(const std::string& h5_file_name, std::span<const XdmfSnapshot> snapshots,
                                        const WallNames& wall_names = {});

/// Writes xdmf_document() to `xdmf_path` atomically (temporary file, then rename),
/// so a reader never sees half a sidecar. Throws dfc::UserError naming the path
/// when it cannot be written.
void write_xdmf(const std::filesystem::path& xdmf_path, const std::string& h5_file_name, std::span<const XdmfSnapshot> snapshots,
                const WallNames& wall_names = {});

}  // namespace dfc::coupler
