#include "dfc/continuum/delaunay_retriangulation.hpp"

#include <cmath>
#include <deque>
#include <numbers>

// GCC's -Wnull-dereference (cmake/Warnings.cmake) fires inside CGAL's
// Compact_container iterators, a false positive of its flow analysis in a
// library header; being a middle-end warning it is not silenced by the system
// include path, so it is switched off for CGAL's headers only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#pragma GCC diagnostic pop

namespace dfc::continuum {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
/// Vertex info: the node index; vertices the refinement adds keep kInterior until numbered.
struct VertexInfo {
  Index node = Retriangulation::kInterior;
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Kernel, CGAL::Delaunay_mesh_vertex_base_2<Kernel>>;
/// Face info: nesting level across constraints from the outside (−1: not reached yet).
using FaceInfoBase = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel, CGAL::Constrained_triangulation_face_base_2<Kernel, FaceInfoBase>>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact predicates, and no intersecting constraints (the boundary is a simple polygon).
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, DataStructure, CGAL::No_constraint_intersection_tag>;

// Faces at odd nesting level (one constraint crossed from the outside, three
// for an island in a hole …) are inside the body: the flood fill of the CGAL
// manual's polygon-triangulation example.
void mark_nesting_levels(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::deque<Cdt::Face_handle> border{cdt.infinite_face()};
  int level = 0;
  while (!border.empty()) {
    std::deque<Cdt::Face_handle> next_border;
    std::deque<Cdt::Face_handle> queue;
    for (const auto& start : border)
      if (start->info() == -1) queue.push_back(start);
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info() != -1) continue;
      f->info() = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle neighbour = f->neighbor(i);
        if (neighbour->info() != -1) continue;
        (cdt.is_constrained(Cdt::Edge(f, i)) ? next_border : queue).push_back(neighbour);
      }
    }
    border = std::move(next_border);
    ++level;
  }
}

/// The edge of `boundary` that `p` lies on (within round-off of its length), or kInterior.
Index boundary_edge_containing(const Point& p, std::span<const Point> nodes, std::span<const Edge> boundary) {
  for (Index e = 0; e < boundary.size(); ++e) {
    const Point& a = nodes[boundary[e][0]];
    const Point& b = nodes[boundary[e][1]];
    const Point along = b - a;
    const double length_squared = along.squaredNorm();
    const double t = (p - a).dot(along) / length_squared;
    if (t <= 0.0 || t >= 1.0) continue;
    if ((a + t * along - p).squaredNorm() <= 1e-20 * length_squared) return e;
  }
  return Retriangulation::kInterior;
}

}  // namespace

Retriangulation delaunay_retriangulation(std::span<const Point> nodes, std::span<const Edge> boundary, double minimum_angle_deg) {
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> vertices;
  vertices.reserve(nodes.size());
  for (Index n = 0; n < nodes.size(); ++n) {
    const Cdt::Vertex_handle v = cdt.insert(Kernel::Point_2(nodes[n].x(), nodes[n].y()));
    v->info().node = n;
    vertices.push_back(v);
  }
  for (const Edge& e : boundary) cdt.insert_constraint(vertices[e[0]], vertices[e[1]]);
  if (minimum_angle_deg > 0.0) {
    // CGAL's shape bound B = sin²(smallest angle); no size bound.
    const double sine = std::sin(minimum_angle_deg * std::numbers::pi / 180.0);
    CGAL::refine_Delaunay_mesh_2(cdt, CGAL::Delaunay_mesh_size_criteria_2<Cdt>(sine * sine, 0.0));
  }
  Retriangulation result;
  Index next = nodes.size();
  // Vertex order is CGAL's storage order, deterministic for the same input.
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    if (v->info().node != Retriangulation::kInterior) continue;
    v->info().node = next++;
    const Point p(v->point().x(), v->point().y());
    result.added_nodes.push_back(p);
    result.boundary_edge_of_added.push_back(boundary_edge_containing(p, nodes, boundary));
  }
  mark_nesting_levels(cdt);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (f->info() % 2 != 1) continue;
    // CGAL lists a face's vertices counter-clockwise.
    result.triangles.push_back({f->vertex(0)->info().node, f->vertex(1)->info().node, f->vertex(2)->info().node});
  }
  return result;
}

}  // namespace dfc::continuum
