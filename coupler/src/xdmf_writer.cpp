#include "dfc/coupler/xdmf_writer.hpp"

#include <charconv>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

#include "dfc/common/errors.hpp"

namespace dfc::coupler {

namespace {

using protocol::DType;

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

// Shortest text that reads back as the same double, so time values survive exactly.
std::string number_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string dimensions_text(const std::vector<std::int64_t>& shape) {
  std::string out;
  for (const std::int64_t d : shape) {
    if (!out.empty()) out += ' ';
    out += std::to_string(d);
  }
  return out;
}

// XDMF NumberType and Precision of each wire dtype.
std::pair<const char*, int> number_type(DType dtype) {
  switch (dtype) {
    case DType::f64: return {"Float", 8};
    case DType::f32: return {"Float", 4};
    case DType::i64: return {"Int", 8};
    case DType::i32: return {"Int", 4};
    case DType::u8: return {"UChar", 1};
  }
  return {"Float", 8};
}

bool is_integer(DType dtype) { return dtype == DType::i64 || dtype == DType::i32; }

const XdmfArrayInfo* find(const XdmfSnapshot& snapshot, std::string_view name) {
  for (const XdmfArrayInfo& array : snapshot.arrays) {
    if (array.name == name) return &array;
  }
  return nullptr;
}

// Point count of an [n, 3] coordinate array, or nothing when it cannot be geometry.
std::optional<std::int64_t> point_count(const XdmfArrayInfo* positions) {
  if (positions == nullptr || positions->shape.size() != 2 || positions->shape[1] != 3 || positions->shape[0] <= 0) return std::nullopt;
  if (positions->dtype != DType::f64 && positions->dtype != DType::f32) return std::nullopt;
  return positions->shape[0];
}

// How a snapshot is drawn: its geometry, and hexahedra when it has them.
struct Layout {
  const XdmfArrayInfo* positions = nullptr;
  const XdmfArrayInfo* zones = nullptr;  ///< null: one vertex per point
  std::int64_t points = 0;
  std::int64_t cells = 0;
};

std::optional<Layout> layout_of(const XdmfSnapshot& snapshot) {
  const bool particles = snapshot.kind == "particles";
  if (!particles && snapshot.kind != "grid") return std::nullopt;  // e.g. bonds or interface data: not a mesh ParaView can show this way
  Layout layout;
  layout.positions = find(snapshot, particles ? "particle_position" : "node_position");
  const std::optional<std::int64_t> points = point_count(layout.positions);
  if (!points) return std::nullopt;
  layout.points = *points;
  const XdmfArrayInfo* zones = particles ? nullptr : find(snapshot, "zone_nodes");
  if (zones != nullptr && zones->shape.size() == 2 && zones->shape[1] == 8 && zones->shape[0] > 0 && is_integer(zones->dtype)) {
    layout.zones = zones;
    layout.cells = zones->shape[0];
  }  // otherwise not a hexahedron connectivity: the nodes are shown as points
  return layout;
}

bool is_index_rows(const XdmfArrayInfo* array, std::int64_t width) {
  return array != nullptr && array->shape.size() == 2 && array->shape[1] == width && array->shape[0] > 0 && is_integer(array->dtype);
}

// Pairs of spheres of a particle snapshot drawn as lines, the bonds
// ("bond_") or the contacts ("contact_"): <prefix>particle_index [m, 2] rows of
// particle_position. Null when the snapshot has none (or an older server
// sent only the bond midpoints).
const XdmfArrayInfo* pair_lines(const XdmfSnapshot& snapshot, const std::string& prefix) {
  if (snapshot.kind != "particles" || !point_count(find(snapshot, "particle_position"))) return nullptr;
  const XdmfArrayInfo* index = find(snapshot, prefix + "particle_index");
  return is_index_rows(index, 2) ? index : nullptr;
}

const XdmfArrayInfo* bond_lines(const XdmfSnapshot& snapshot) { return pair_lines(snapshot, "bond_"); }

// Bond midpoints of a particle snapshot (bond_position [m, 3] with bond_state [m])
// from a server that sends no bond_particle_index: m, or nothing when the
// snapshot has no bonds to draw as points.
std::optional<std::int64_t> bond_count(const XdmfSnapshot& snapshot) {
  if (snapshot.kind != "particles" || bond_lines(snapshot) != nullptr) return std::nullopt;
  const std::optional<std::int64_t> points = point_count(find(snapshot, "bond_position"));
  const XdmfArrayInfo* state = find(snapshot, "bond_state");
  if (!points || state == nullptr || state->shape.size() != 1 || state->shape[0] != *points) return std::nullopt;
  return points;
}

// The walls and the pile of a particle snapshot: wall_facets [f, 3] rows of wall_vertices.
const XdmfArrayInfo* wall_triangles(const XdmfSnapshot& snapshot) {
  if (snapshot.kind != "particles" || !point_count(find(snapshot, "wall_vertices"))) return nullptr;
  const XdmfArrayInfo* facets = find(snapshot, "wall_facets");
  return is_index_rows(facets, 3) ? facets : nullptr;
}

// The name ParaView shows: the array's name with its unit where the name
// does not already end in one (protocol/SPEC.md §6.4 fixes the dataset names,
// so the unit is added here, not in the file).
std::string display_name(const std::string& name) {
  static const std::pair<std::string_view, std::string_view> named[] = {
      {"particle_radius", "particle_radius_m"},         {"particle_velocity", "particle_velocity_m_s"},
      {"node_displacement", "node_displacement_m"},     {"node_velocity", "node_velocity_m_s"},
      {"node_external_force", "node_external_force_n"}, {"zone_stress", "zone_stress_pa"},
      {"wall_facet_wall", "wall_index"},
  };
  for (const auto& [from, to] : named)
    if (name == from) return std::string(to);
  return name;
}

// XDMF AttributeType from the per-entity component count; nothing for shapes ParaView cannot label.
std::optional<const char*> attribute_type(const XdmfArrayInfo& array) {
  if (array.shape.size() == 1) return "Scalar";
  if (array.shape.size() != 2) return std::nullopt;
  switch (array.shape[1]) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 6: return "Tensor6";
    case 9: return "Tensor";
    default: return std::nullopt;
  }
}

class GridWriter {
 public:
  GridWriter(std::ostringstream& out, const std::string& h5_file_name) : out_(out), h5_file_name_(h5_file_name) {}

  void data_item(const XdmfSnapshot& snapshot, const XdmfArrayInfo& array, const char* indent) {
    const auto [type, precision] = number_type(array.dtype);
    out_ << indent << "<DataItem Dimensions=\"" << dimensions_text(array.shape) << "\" NumberType=\"" << type << "\" Precision=\""
         << precision << "\" Format=\"HDF\">" << escape(h5_file_name_) << ':' << escape(snapshot.group_path) << '/' << escape(array.name)
         << "</DataItem>\n";
  }

  void attribute(const XdmfSnapshot& snapshot, const XdmfArrayInfo& array, const char* center) {
    const std::optional<const char*> type = attribute_type(array);
    if (!type) return;
    out_ << "        <Attribute Name=\"" << escape(display_name(array.name)) << "\" AttributeType=\"" << *type << "\" Center=\"" << center << "\">\n";
    data_item(snapshot, array, "          ");
    out_ << "        </Attribute>\n";
  }

  // Pairs as lines between the two sphere centres (<prefix>particle_index
  // into particle_position) with every other <prefix>* array of one row per
  // pair as a cell attribute; <prefix>position (a point per pair) is not one.
  void line_grid(const XdmfSnapshot& snapshot, const XdmfArrayInfo& index, const std::string& prefix, const char* infix) {
    const std::int64_t lines = index.shape[0];
    open_grid(snapshot, infix);
    out_ << "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << lines << "\" NodesPerElement=\"2\">\n";
    data_item(snapshot, index, "          ");
    out_ << "        </Topology>\n";
    geometry(snapshot, *find(snapshot, "particle_position"));
    for (const XdmfArrayInfo& array : snapshot.arrays) {
      if (!array.name.starts_with(prefix) || &array == &index || array.name == prefix + "position" || array.shape.empty() ||
          array.shape[0] != lines)
        continue;
      attribute(snapshot, array, "Cell");
    }
    out_ << "      </Grid>\n";
  }

  // The bonds of a particle snapshot as lines with their state (1 intact, 2
  // damaged, 3 broken in tension, 4 broken in shear), forces, opening,
  // damage. From an older server, points at the midpoints (bond_position)
  // with their state and damage.
  void bond_grid(const XdmfSnapshot& snapshot) {
    if (const XdmfArrayInfo* index = bond_lines(snapshot)) {
      line_grid(snapshot, *index, "bond_", "_bonds_");
      return;
    }
    const std::optional<std::int64_t> bonds = bond_count(snapshot);
    const XdmfArrayInfo* position = find(snapshot, "bond_position");
    const XdmfArrayInfo* state = find(snapshot, "bond_state");
    if (!bonds || position == nullptr || state == nullptr) return;  // bond_count checked them; said again for the reader (and GCC)
    open_grid(snapshot, "_bonds_");
    polyvertex_topology(*bonds);
    geometry(snapshot, *position);
    attribute(snapshot, *state, "Node");
    if (const XdmfArrayInfo* damage = find(snapshot, "bond_damage")) attribute(snapshot, *damage, "Node");  // damage_bond's D
    out_ << "      </Grid>\n";
  }

  // The contact network of a particle snapshot as lines with their normal
  // force (compression positive) and force vector: force chains.
  void contact_grid(const XdmfSnapshot& snapshot) {
    if (const XdmfArrayInfo* index = pair_lines(snapshot, "contact_")) line_grid(snapshot, *index, "contact_", "_contacts_");
  }

  // The walls and the pile of a particle snapshot as triangles where they are
  // at that time, with the index of the wall each facet belongs to.
  void wall_grid(const XdmfSnapshot& snapshot) {
    const XdmfArrayInfo* facets = wall_triangles(snapshot);
    if (facets == nullptr) return;
    open_grid(snapshot, "_walls_");
    out_ << "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << facets->shape[0] << "\">\n";
    data_item(snapshot, *facets, "          ");
    out_ << "        </Topology>\n";
    geometry(snapshot, *find(snapshot, "wall_vertices"));
    if (const XdmfArrayInfo* wall = find(snapshot, "wall_facet_wall"); wall != nullptr && wall->shape.size() == 1 && wall->shape[0] == facets->shape[0])
      attribute(snapshot, *wall, "Cell");
    out_ << "      </Grid>\n";
  }

  // One uniform grid for `snapshot`, or nothing when it has no usable geometry.
  void grid(const XdmfSnapshot& snapshot) {
    const std::optional<Layout> layout = layout_of(snapshot);
    if (!layout) return;
    const XdmfArrayInfo* positions = layout->positions;
    const XdmfArrayInfo* zones = layout->zones;
    const std::int64_t points = layout->points;
    const std::int64_t cells = layout->cells;

    open_grid(snapshot, "_");
    if (zones != nullptr) {
      out_ << "        <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"" << cells << "\">\n";
      data_item(snapshot, *zones, "          ");
      out_ << "        </Topology>\n";
    } else {
      polyvertex_topology(points);
    }
    geometry(snapshot, *positions);

    for (const XdmfArrayInfo& array : snapshot.arrays) {
      if (&array == positions || &array == zones || array.shape.empty()) continue;
      const std::int64_t leading = array.shape[0];
      const bool zone_named = array.name.starts_with("zone_");
      // When node and zone counts coincide the name decides; otherwise the count does.
      if (zones != nullptr && leading == cells && (leading != points || zone_named)) {
        attribute(snapshot, array, "Cell");
      } else if (leading == points) {
        attribute(snapshot, array, "Node");
      }
    }
    out_ << "      </Grid>\n";
  }

 private:
  // Opens the uniform grid of `snapshot` named <role><infix><index>, at its time.
  void open_grid(const XdmfSnapshot& snapshot, const char* infix) {
    const std::string index = snapshot.group_path.substr(snapshot.group_path.find_last_of('/') + 1);
    out_ << "      <Grid Name=\"" << escape(snapshot.role + infix + index) << "\" GridType=\"Uniform\">\n";
    out_ << "        <Time Value=\"" << number_text(snapshot.time) << "\"/>\n";
  }

  void polyvertex_topology(std::int64_t points) {
    out_ << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << points << "\" NodesPerElement=\"1\">\n";
    out_ << "          <DataItem Dimensions=\"" << points << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << escape(h5_file_name_)
         << ':' << polyvertex_connectivity_path(points) << "</DataItem>\n";
    out_ << "        </Topology>\n";
  }

  void geometry(const XdmfSnapshot& snapshot, const XdmfArrayInfo& positions) {
    out_ << "        <Geometry GeometryType=\"XYZ\">\n";
    data_item(snapshot, positions, "          ");
    out_ << "        </Geometry>\n";
  }

  std::ostringstream& out_;
  const std::string& h5_file_name_;
};

}  // namespace

std::optional<std::int64_t> polyvertex_point_count(const XdmfSnapshot& snapshot) {
  const std::optional<Layout> layout = layout_of(snapshot);
  if (!layout || layout->zones != nullptr) return std::nullopt;
  return layout->points;
}

std::optional<std::int64_t> bond_point_count(const XdmfSnapshot& snapshot) { return bond_count(snapshot); }

std::string polyvertex_connectivity_path(std::int64_t points) { return "/xdmf/polyvertex_" + std::to_string(points); }

std::string xdmf_document(const std::string& h5_file_name, std::span<const XdmfSnapshot> snapshots, const WallNames& wall_names) {
  // Roles in order of first appearance, so the collections follow the run.
  std::vector<std::string> roles;
  for (const XdmfSnapshot& snapshot : snapshots) {
    bool seen = false;
    for (const std::string& role : roles) seen = seen || role == snapshot.role;
    if (!seen) roles.push_back(snapshot.role);
  }

  std::ostringstream out;
  out << "<?xml version=\"1.0\" ?>\n";
  out << "<Xdmf Version=\"2.0\">\n";
  out << "  <Domain>\n";
  // Per role: its particles or grid, then the bonds, the contacts and the walls of its particle snapshots.
  using Layer = void (GridWriter::*)(const XdmfSnapshot&);
  const std::pair<const char*, Layer> layers[] = {
      {"", &GridWriter::grid}, {"_bonds", &GridWriter::bond_grid}, {"_contacts", &GridWriter::contact_grid}, {"_walls", &GridWriter::wall_grid}};
  for (const std::string& role : roles) {
    for (const auto& [suffix, layer] : layers) {
      std::ostringstream grids;
      GridWriter writer(grids, h5_file_name);
      std::string kind;
      for (const XdmfSnapshot& snapshot : snapshots) {
        if (snapshot.role != role) continue;
        (writer.*layer)(snapshot);
        if (kind.empty() && (snapshot.kind == "particles" || snapshot.kind == "grid")) kind = snapshot.kind;
      }
      if (grids.str().empty()) continue;  // an empty temporal collection makes readers fail
      // The block's name says what it holds: dem_particles, continuum_grid, dem_bonds, dem_contacts, dem_walls.
      const std::string name = role + (*suffix != '\0' ? std::string(suffix) : "_" + kind);
      out << "    <Grid Name=\"" << escape(name) << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
      if (const auto names = wall_names.find(role); layer == &GridWriter::wall_grid && names != wall_names.end() && !names->second.empty()) {
        std::string listed;
        for (std::size_t w = 0; w < names->second.size(); ++w) listed += (w ? "; " : "") + std::to_string(w) + " " + names->second[w];
        out << "      <Information Name=\"wall_index\" Value=\"" << escape(listed) << "\"/>\n";
      }
      out << grids.str();
      out << "    </Grid>\n";
    }
  }
  out << "  </Domain>\n";
  out << "</Xdmf>\n";
  return out.str();
}

void write_xdmf(const std::filesystem::path& xdmf_path, const std::string& h5_file_name, std::span<const XdmfSnapshot> snapshots,
                const WallNames& wall_names) {
  const std::string text = xdmf_document(h5_file_name, snapshots, wall_names);
  std::filesystem::path temporary = xdmf_path;
  temporary += ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text;
    file.flush();
    if (!file) throw UserError("cannot write XDMF sidecar '" + temporary.string() + "'; check that the directory is writable and not full.");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, xdmf_path, ec);
  if (ec) {
    const std::string reason = ec.message();
    std::filesystem::remove(temporary, ec);
    throw UserError("cannot write XDMF sidecar '" + xdmf_path.string() + "' (" + reason + "); check that the directory is writable.");
  }
}

}  // namespace dfc::coupler
