// XDMF sidecar: well-formed XML whose every DataItem names a dataset that
// exists in the HDF5 file with the stated dimensions, and the mesh description
// ParaView needs for particles and grids.
#include "dfc/coupler/xdmf_writer.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "dfc/common/errors.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "dfc/coupler/results_writer.hpp"
#include "results_sample_data.hpp"

namespace dfc::coupler {
namespace {

using namespace dfc::coupler::testing;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Empty when `xml` is well formed as far as element nesting and attribute
/// quoting go (enough for generated XML without comments or CDATA); otherwise why not.
std::string nesting_error(const std::string& xml) {
  std::vector<std::string> open;
  std::size_t at = 0;
  while ((at = xml.find('<', at)) != std::string::npos) {
    const std::size_t end = xml.find('>', at);
    if (end == std::string::npos) return "unterminated tag at " + std::to_string(at);
    const std::string tag = xml.substr(at + 1, end - at - 1);
    at = end + 1;
    if (tag.starts_with('?')) {
      if (!tag.ends_with('?')) return "bad processing instruction";
      continue;
    }
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return "unbalanced quotes in <" + tag + ">";
    if (tag.starts_with('/')) {
      if (open.empty() || open.back() != tag.substr(1)) return "unexpected </" + tag.substr(1) + ">";
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
    if (name.empty()) return "empty tag name";
    if (!tag.ends_with('/')) open.push_back(name);
  }
  return open.empty() ? "" : "unclosed <" + open.back() + ">";
}

struct DataItemRef {
  std::vector<std::int64_t> dimensions;
  std::string file;
  std::string path;
};

std::vector<DataItemRef> data_items(const std::string& xml) {
  std::vector<DataItemRef> refs;
  const std::regex item(R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*Format="HDF">([^<:]+):([^<]+)</DataItem>)re");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), item); it != std::sregex_iterator(); ++it) {
    DataItemRef ref;
    std::istringstream dims((*it)[1].str());
    for (std::int64_t d = 0; dims >> d;) ref.dimensions.push_back(d);
    ref.file = (*it)[2].str();
    ref.path = (*it)[3].str();
    refs.push_back(ref);
  }
  return refs;
}

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

class ResultsXdmf : public ::testing::Test {
 protected:
  // Not short decimals, so a time printed with too few digits would not read back equal.
  static double time_of(int k) { return 0.1 * k + 1.0 / 3.0; }

  ResultsXdmf() : dir_("xdmf") {
    ResultsWriter out(dir_ / "run.h5", nlohmann::json::object(), nlohmann::json::object());
    for (int k = 0; k < 3; ++k) {
      out.write_snapshot("dem", 100 * k, time_of(k), "particles", particle_arrays(6, k));
      out.write_snapshot("fdm", 100 * k, time_of(k), "grid", grid_arrays(2, 2, 1, k));
    }
    out.write_snapshot("dem", 300, 0.3, "bonds", {});  // not a mesh: left out of the sidecar
    out.close();
    xml_ = read_text(dir_ / "run.xdmf");
  }
  ScratchDir dir_;
  std::string xml_;
};

TEST_F(ResultsXdmf, IsWellFormed) {
  ASSERT_FALSE(xml_.empty());
  EXPECT_EQ(nesting_error(xml_), "");
  EXPECT_TRUE(xml_.starts_with("<?xml"));
}

TEST_F(ResultsXdmf, ReferencesOnlyExistingDatasetsWithTheirShapes) {
  const std::vector<DataItemRef> refs = data_items(xml_);
  // dem: connectivity, position, radius, velocity, id per snapshot; fdm: zones, positions, 2 node vectors, stress.
  EXPECT_EQ(refs.size(), 3U * 5U + 3U * 5U);
  const h5::File in = h5::File::open_read_only(dir_ / "run.h5");
  for (const DataItemRef& ref : refs) {
    SCOPED_TRACE(ref.path);
    EXPECT_EQ(ref.file, "run.h5");  // relative, so the pair can be moved together
    ASSERT_TRUE(h5::exists(in, ref.path));
    EXPECT_EQ(h5::dataset_shape(in, ref.path), ref.dimensions);
  }
}

TEST_F(ResultsXdmf, PolyvertexConnectivityIsStoredOnce) {
  const h5::File in = h5::File::open_read_only(dir_ / "run.h5");
  EXPECT_EQ(h5::list_members(in, "/xdmf"), (std::vector<std::string>{"polyvertex_6"}));
  EXPECT_EQ(h5::read_i64(in, "/xdmf/polyvertex_6"), (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5}));
}

TEST_F(ResultsXdmf, DescribesParticlesAndGridOverTime) {
  EXPECT_EQ(count(xml_, "CollectionType=\"Temporal\""), 2U);
  EXPECT_EQ(count(xml_, "<Time Value="), 6U);
  EXPECT_EQ(count(xml_, "TopologyType=\"Polyvertex\" NumberOfElements=\"6\""), 3U);
  EXPECT_EQ(count(xml_, "TopologyType=\"Hexahedron\" NumberOfElements=\"4\""), 3U);
  // Names say the quantity's unit where the dataset's name does not.
  EXPECT_EQ(count(xml_, "<Attribute Name=\"zone_stress_pa\" AttributeType=\"Tensor6\" Center=\"Cell\">"), 3U);
  EXPECT_EQ(count(xml_, "<Attribute Name=\"node_displacement_m\" AttributeType=\"Vector\" Center=\"Node\">"), 3U);
  EXPECT_EQ(count(xml_, "<Attribute Name=\"particle_radius_m\" AttributeType=\"Scalar\" Center=\"Node\">"), 3U);
  EXPECT_EQ(count(xml_, "<Attribute Name=\"particle_velocity_m_s\" AttributeType=\"Vector\" Center=\"Node\">"), 3U);
  EXPECT_EQ(count(xml_, "<Attribute Name=\"particle_id\" AttributeType=\"Scalar\" Center=\"Node\">"), 3U);
  EXPECT_EQ(count(xml_, "wall_force"), 0U);  // leading dimension is not the particle count
  // Blocks are named for what they hold.
  EXPECT_EQ(count(xml_, "<Grid Name=\"dem_particles\" GridType=\"Collection\""), 1U);
  EXPECT_EQ(count(xml_, "<Grid Name=\"fdm_grid\" GridType=\"Collection\""), 1U);
}

TEST_F(ResultsXdmf, TimesReadBackExactly) {
  const std::regex time(R"re(<Time Value="([^"]+)"/>)re");
  std::vector<double> times;
  for (auto it = std::sregex_iterator(xml_.begin(), xml_.end(), time); it != std::sregex_iterator(); ++it)
    times.push_back(std::strtod((*it)[1].str().c_str(), nullptr));
  const std::vector<double> expected = {time_of(0), time_of(1), time_of(2), time_of(0), time_of(1), time_of(2)};  // dem, then fdm
  EXPECT_EQ(times, expected);
}

TEST(XdmfDocument, LeavesOutSnapshotsWithoutGeometryAndEscapesNames) {
  XdmfSnapshot no_geometry{"dem", "/snapshots/dem/000000", 0, 0.0, "particles", {{"particle_radius", protocol::DType::f64, {4}}}};
  XdmfSnapshot odd_name{"a&b", "/snapshots/a&b/000000", 0, 0.0, "particles",
                        {{"particle_position", protocol::DType::f64, {2, 3}}, {"x<y", protocol::DType::f64, {2}}}};
  const std::vector<XdmfSnapshot> snapshots = {no_geometry, odd_name};
  const std::string xml = xdmf_document("r.h5", snapshots);
  EXPECT_EQ(nesting_error(xml), "");
  EXPECT_EQ(count(xml, "<Grid Name=\"dem\""), 0U);  // an empty temporal collection would break readers
  EXPECT_EQ(count(xml, "<Grid Name=\"a&amp;b_particles\""), 1U);  // the block, named for what it holds
  EXPECT_EQ(count(xml, "Name=\"x&lt;y\""), 1U);
}

TEST(XdmfDocument, GridWithoutHexahedraIsShownAsPoints) {
  XdmfSnapshot grid{"fdm", "/snapshots/fdm/000000", 0, 0.0, "grid",
                    {{"node_position", protocol::DType::f64, {8, 3}}, {"zone_nodes", protocol::DType::i64, {1, 4}}}};
  const std::vector<XdmfSnapshot> snapshots = {grid};
  const std::string xml = xdmf_document("r.h5", snapshots);
  EXPECT_EQ(count(xml, "TopologyType=\"Polyvertex\" NumberOfElements=\"8\""), 1U);
  EXPECT_EQ(count(xml, "Hexahedron"), 0U);
}

TEST(XdmfDocument, BondsOfAnOlderServerAreASecondCollectionOfPointsWithTheirState) {
  // Three bonds among four particles from a server that sends no
  // bond_particle_index: the bonds' own collection, points at the midpoints
  // (bond_position) labelled by bond_state, beside the particles.
  XdmfSnapshot dem{"dem", "/snapshots/dem/000000", 0, 0.5, "particles",
                   {{"particle_position", protocol::DType::f64, {4, 3}},
                    {"bond_position", protocol::DType::f64, {3, 3}},
                    {"bond_state", protocol::DType::i64, {3}}}};
  const std::vector<XdmfSnapshot> snapshots = {dem};
  const std::string xml = xdmf_document("r.h5", snapshots);
  EXPECT_EQ(nesting_error(xml), "");
  ASSERT_EQ(bond_point_count(dem), std::optional<std::int64_t>(3));
  EXPECT_EQ(count(xml, "<Grid Name=\"dem_bonds\" GridType=\"Collection\" CollectionType=\"Temporal\">"), 1U);
  EXPECT_EQ(count(xml, "TopologyType=\"Polyvertex\" NumberOfElements=\"3\""), 1U);
  EXPECT_EQ(count(xml, "TopologyType=\"Polyvertex\" NumberOfElements=\"4\""), 1U);
  EXPECT_EQ(count(xml, "r.h5:/snapshots/dem/000000/bond_position</DataItem>"), 1U);
  EXPECT_EQ(count(xml, "<Attribute Name=\"bond_state\" AttributeType=\"Scalar\" Center=\"Node\">"), 1U);
  // A bond_state that does not match the positions is not drawn.
  dem.arrays.back().shape = {2};
  EXPECT_EQ(bond_point_count(dem), std::nullopt);
}

TEST(XdmfDocument, BondsAreLinesBetweenTheSphereCentresWithTheirArraysOnTheCells) {
  // Three bonds among four particles: Polyline cells of two nodes whose
  // connectivity is bond_particle_index and whose points are the particles'.
  XdmfSnapshot dem{"dem", "/snapshots/dem/000002", 0, 0.5, "particles",
                   {{"particle_position", protocol::DType::f64, {4, 3}},
                    {"bond_position", protocol::DType::f64, {3, 3}},
                    {"bond_state", protocol::DType::i64, {3}},
                    {"bond_particle_index", protocol::DType::i64, {3, 2}},
                    {"bond_particle_id", protocol::DType::i64, {3, 2}},
                    {"bond_normal_force_n", protocol::DType::f64, {3}},
                    {"bond_shear_force_n", protocol::DType::f64, {3}},
                    {"bond_opening_m", protocol::DType::f64, {3}}}};
  const std::vector<XdmfSnapshot> snapshots = {dem};
  const std::string xml = xdmf_document("r.h5", snapshots);
  EXPECT_EQ(nesting_error(xml), "");
  EXPECT_EQ(bond_point_count(dem), std::nullopt);  // lines need no Polyvertex connectivity
  EXPECT_EQ(count(xml, "<Grid Name=\"dem_bonds\" GridType=\"Collection\" CollectionType=\"Temporal\">"), 1U);
  EXPECT_EQ(count(xml, "<Grid Name=\"dem_bonds_000002\""), 1U);
  EXPECT_EQ(count(xml, "<Topology TopologyType=\"Polyline\" NumberOfElements=\"3\" NodesPerElement=\"2\">\n          <DataItem Dimensions=\"3 2\""), 1U);
  EXPECT_EQ(count(xml, "r.h5:/snapshots/dem/000002/bond_particle_index</DataItem>"), 1U);
  EXPECT_EQ(count(xml, "r.h5:/snapshots/dem/000002/particle_position</DataItem>"), 2U);  // the particles' and the bonds' geometry
  EXPECT_EQ(count(xml, "bond_position"), 0U);
  for (const char* name : {"bond_state", "bond_normal_force_n", "bond_shear_force_n", "bond_opening_m"})
    EXPECT_EQ(count(xml, std::string("<Attribute Name=\"") + name + "\" AttributeType=\"Scalar\" Center=\"Cell\">"), 1U) << name;
  EXPECT_EQ(count(xml, "Name=\"bond_particle_id\""), 0U);  // two values per cell: in the file, not a ParaView attribute
  // An index array that is not two integer columns is not a line connectivity: the midpoints again.
  dem.arrays[3].shape = {3, 3};
  EXPECT_EQ(bond_point_count(dem), std::optional<std::int64_t>(3));
}

TEST(XdmfDocument, ContactsAreLinesWithTheirForcesBesideTheBonds) {
  // Two contacts and one bond among four particles: a block of its own,
  // dem_contacts, after dem_bonds; the force vector is a Vector on the cells.
  const XdmfSnapshot dem{"dem", "/snapshots/dem/000003", 0, 0.5, "particles",
                         {{"particle_position", protocol::DType::f64, {4, 3}},
                          {"bond_state", protocol::DType::i64, {1}},
                          {"bond_particle_index", protocol::DType::i64, {1, 2}},
                          {"contact_particle_index", protocol::DType::i64, {2, 2}},
                          {"contact_normal_force_n", protocol::DType::f64, {2}},
                          {"contact_force_n", protocol::DType::f64, {2, 3}}}};
  const std::vector<XdmfSnapshot> snapshots = {dem};
  const std::string xml = xdmf_document("r.h5", snapshots);
  EXPECT_EQ(nesting_error(xml), "");
  EXPECT_EQ(count(xml, "<Grid Name=\"dem_contacts\" GridType=\"Collection\" CollectionType=\"Temporal\">"), 1U);
  EXPECT_LT(xml.find("Name=\"dem_bonds\""), xml.find("Name=\"dem_contacts\""));
  EXPECT_EQ(count(xml, "<Topology TopologyType=\"Polyline\" NumberOfElements=\"2\" NodesPerElement=\"2\">\n          <DataItem Dimensions=\"2 2\""), 1U);
  EXPECT_EQ(count(xml, "r.h5:/snapshots/dem/000003/contact_particle_index</DataItem>"), 1U);
  EXPECT_EQ(count(xml, "<Attribute Name=\"contact_normal_force_n\" AttributeType=\"Scalar\" Center=\"Cell\">"), 1U);
  EXPECT_EQ(count(xml, "<Attribute Name=\"contact_force_n\" AttributeType=\"Vector\" Center=\"Cell\">"), 1U);
  EXPECT_EQ(count(xml, "Name=\"bond_state\""), 1U);  // the bonds keep their own arrays; no contact array on them
  // Without contacts (before the first step, or left out by the scenario) there is no block.
  XdmfSnapshot none = dem;
  none.arrays[3].shape = {0, 2};
  const std::vector<XdmfSnapshot> empty = {none};
  EXPECT_EQ(count(xdmf_document("r.h5", empty), "dem_contacts"), 0U);
}

TEST(XdmfDocument, WallsAndThePileAreTrianglesWithTheirWallIndex) {
  XdmfSnapshot dem{"dem", "/snapshots/dem/000001", 0, 0.5, "particles",
                   {{"particle_position", protocol::DType::f64, {4, 3}},
                    {"wall_vertices", protocol::DType::f64, {9, 3}},
                    {"wall_facets", protocol::DType::i64, {8, 3}},
                    {"wall_facet_wall", protocol::DType::i64, {8}}}};
  const std::vector<XdmfSnapshot> snapshots = {dem, dem};
  const std::string xml = xdmf_document("r.h5", snapshots);
  EXPECT_EQ(nesting_error(xml), "");
  EXPECT_EQ(count(xml, "<Grid Name=\"dem_walls\" GridType=\"Collection\" CollectionType=\"Temporal\">"), 1U);
  EXPECT_EQ(count(xml, "<Topology TopologyType=\"Triangle\" NumberOfElements=\"8\">"), 2U);
  EXPECT_EQ(count(xml, "r.h5:/snapshots/dem/000001/wall_vertices</DataItem>"), 2U);
  EXPECT_EQ(count(xml, "<Attribute Name=\"wall_index\" AttributeType=\"Scalar\" Center=\"Cell\">"), 2U);
  EXPECT_EQ(count(xml, "Name=\"wall_vertices\""), 0U);  // not a particle attribute (9 rows, not 4)
  EXPECT_EQ(count(xml, "<Information"), 0U);              // no names given
  // With the walls' names: one Information on the walls collection that
  // lists each index with its name, escaped; none for a role without names.
  const std::string named = xdmf_document("r.h5", snapshots, {{"dem", {"floor", "pile", "a<b"}}, {"continuum", {"x"}}});
  EXPECT_EQ(nesting_error(named), "");
  EXPECT_EQ(count(named, "<Information Name=\"wall_index\" Value=\"0 floor; 1 pile; 2 a&lt;b\"/>"), 1U) << named;
  EXPECT_LT(named.find("<Grid Name=\"dem_walls\""), named.find("<Information"));
  EXPECT_EQ(count(named, "<Information"), 1U);
  // Facets that are not three integer columns draw no walls.
  dem.arrays[2].shape = {8, 4};
  const std::vector<XdmfSnapshot> bad = {dem};
  EXPECT_EQ(count(xdmf_document("r.h5", bad), "dem_walls"), 0U);
}

TEST(XdmfDocument, UnwritableSidecarIsUserError) {
  const std::vector<XdmfSnapshot> none;
  EXPECT_THROW(write_xdmf("/nonexistent-dfc-dir/run.xdmf", "run.h5", none), UserError);
}

}  // namespace
}  // namespace dfc::coupler
