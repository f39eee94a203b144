// Helpers the mesh sources share.
#pragma once

#include <tandem/mesh.h>

namespace tandem {

// Adds every tetrahedron edge (once), and, unless the mesh has triangles already, the boundary:
// faces used by one tet only, wound outwards. Tets must be positively oriented.
void addTetEdgesAndBoundary(DeformableMesh& mesh);

}  // namespace tandem
