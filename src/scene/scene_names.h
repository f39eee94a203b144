// The words scene files use for Tandem's enums, shared by the reader and the writer.
#pragma once

#include <tandem/scene_file.h>

#include <string>
#include <utility>
#include <vector>

namespace tandem::scene {

template <class T>
using Names = std::vector<std::pair<std::string, T>>;

inline const Names<ShapeType> kShapeNames{{"box", ShapeType::Box},
                                          {"sphere", ShapeType::Sphere},
                                          {"cylinder", ShapeType::Cylinder},
                                          {"capsule", ShapeType::Capsule},
                                          {"plane", ShapeType::Plane},
                                          {"convex_hull", ShapeType::ConvexHull},
                                          {"triangle_mesh", ShapeType::TriangleMesh},
                                          {"compound", ShapeType::Compound}};
// "mesh" is a shape type of scene files that is no ShapeType: a convex hull or a compound made
// from a closed mesh file (SceneMeshShape).
inline const Names<MeshCollision> kMeshCollisionNames{{"convex_hull", MeshCollision::ConvexHull},
                                                      {"hull_per_group", MeshCollision::HullPerGroup},
                                                      {"hull_per_piece", MeshCollision::HullPerPiece}};
inline const Names<SceneJoint::Kind> kJointNames{{"hinge", SceneJoint::Kind::Hinge}, {"fixed", SceneJoint::Kind::Fixed}};
inline const Names<SceneMesh::Kind> kMeshNames{{"rope", SceneMesh::Kind::Rope},
                                               {"cloth_grid", SceneMesh::Kind::ClothGrid},
                                               {"tet_box", SceneMesh::Kind::TetBox},
                                               {"tet_cylinder", SceneMesh::Kind::TetCylinder},
                                               {"obj", SceneMesh::Kind::Obj},
                                               {"tetgen", SceneMesh::Kind::TetGen}};
inline const Names<ParadigmType> kParadigmNames{{"mass_spring", ParadigmType::MassSpring},
                                                {"shape_matching", ParadigmType::ShapeMatching},
                                                {"position_based", ParadigmType::PositionBased},
                                                {"corotational_fem", ParadigmType::CorotationalFem}};
inline const Names<InextensibilityMode> kInextensibilityModeNames{
    {"resist_both", InextensibilityMode::ResistBoth},
    {"resist_compression", InextensibilityMode::ResistCompression},
    {"resist_stretch", InextensibilityMode::ResistStretch}};
inline const Names<RowSolverKind> kRowSolverNames{
    {"auto", RowSolverKind::Auto}, {"direct", RowSolverKind::Direct}, {"iterative", RowSolverKind::Iterative}};
inline const Names<FrictionModel> kFrictionModelNames{{"coulomb", FrictionModel::Coulomb},
                                                      {"pressure", FrictionModel::Pressure}};

template <class T>
std::string nameOf(const Names<T>& names, T value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "";
}

}  // namespace tandem::scene
