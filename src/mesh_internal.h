// Helpers the mesh sources share.
#pragma once

#include <tandem/mesh.h>

#include <string>

namespace tandem {

// Adds every tetrahedron edge (once), and, unless the mesh has triangles already, the boundary:
// faces used by one tet only, wound outwards. Tets must be positively oriented.
void addTetEdgesAndBoundary(DeformableMesh& mesh);

// Refuses a mesh of this many nodes, triangles and tetrahedra (counted in double, so a product of
// dimensions cannot overflow) past `limits`: "<who>: <shape> is N nodes, more than the limit of
// M (Limits::maxNodes ...)". `shape` says where the count comes from ("3000 x 3000 nodes").
Status checkMeshSize(double nodes, double triangles, double tetrahedra, const Limits& limits, const std::string& who,
                     const std::string& shape);

}  // namespace tandem
