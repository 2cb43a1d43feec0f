#pragma once
// Structured mesh generators: model-building functions that append nodes and one part to a Model.
// Numbering: new node ids continue after the largest id in the model, new element ids after the
// largest element id of every part, so ids stay unique across parts. Nodes are NOT merged with
// those of earlier parts; call merge_coincident_nodes (node_merging.h) for that.
//
// Orientation (what the element kernels rely on):
//   Hex8   LS-DYNA order (model.h), every corner Jacobian > 0 for the undistorted mesh.
//   Shell4 counter-clockwise around the normal: plate normal = e1 x e2, sphere normal outward.
// Implementations: one file per generator (generate_box.cpp, generate_plate.cpp, ...).
#include <array>

#include "core/vec3.h"
#include "solver/model/model.h"

namespace crashlink::model {

/// A rectangular block of hexahedra, edges parallel to the axes.
struct BoxMesh {
  Vec3 origin_m{};                 ///< corner with the smallest coordinates [m]
  Vec3 size_m{};                   ///< lx, ly, lz > 0 [m]
  std::array<int, 3> divisions{};  ///< nx, ny, nz >= 1 elements per edge
};

/// A parallelogram of quadrilateral shells spanned by two edge vectors from an origin.
struct PlateMesh {
  Vec3 origin_m{};
  Vec3 edge1_m{};                  ///< first edge (length lx) [m]
  Vec3 edge2_m{};                  ///< second edge (length ly) [m]; normal = edge1 x edge2
  std::array<int, 2> divisions{};  ///< n1, n2 >= 1 elements along edge1, edge2
  /// > 0: interior nodes moved in the plane by up to this fraction of the smaller element edge,
  /// deterministically (a fixed pseudo-random sequence). For distorted-mesh tests; area unchanged.
  double distort = 0.0;
};

/// A straight bar: one row of hexahedra along a coordinate axis, rectangular cross-section.
struct BarMesh {
  Vec3 origin_m{};  ///< centre of the first end face [m]
  int axis = 0;     ///< 0, 1, 2: bar along +x, +y, +z
  double length_m = 0.0;
  std::array<double, 2> cross_section_m{};   ///< sides along the next two axes (cyclic) [m]
  int elements = 0;                          ///< >= 1 hexahedra along the bar
  std::array<int, 2> cross_divisions{1, 1};  ///< elements across each side
};

/// A sphere surface of quadrilateral shells: a "cube-sphere" (6 cube faces, each an n x n grid,
/// projected radially with the equiangular map x = tan(pi/4 * u), u uniform in [-1, 1], which
/// spreads the element sizes far more evenly than the plain gnomonic map x = u).
struct SphereMesh {
  Vec3 centre_m{};
  double radius_m = 0.0;
  int divisions = 0;  ///< n >= 1 elements along each cube edge: 6 n^2 quads
};

/// Appends the box's (nx+1)(ny+1)(nz+1) nodes and nx*ny*nz Hex8 elements. `part` carries name,
/// material and section; its kind is set to Hex8. Returns the index of the new part.
int generate_box(Model& m, Part part, const BoxMesh& box);

/// Appends (n1+1)(n2+1) nodes and n1*n2 Shell4 elements. Returns the index of the new part.
int generate_plate(Model& m, Part part, const PlateMesh& plate);

/// Appends a bar of Hex8 elements (a box along `axis`). Returns the index of the new part.
int generate_bar(Model& m, Part part, const BarMesh& bar);

/// Appends 6 n^2 + 2 nodes (all on the sphere) and 6 n^2 Shell4 elements with outward normals.
int generate_sphere(Model& m, Part part, const SphereMesh& sphere);

/// Next free node id (1 for an empty model) and next free element id.
std::int64_t next_node_id(const Model& m);
std::int64_t next_element_id(const Model& m);

/// Appends the part, filling element ids from next_element_id; returns its index.
int append_part(Model& m, Part part);

}  // namespace crashlink::model
