#pragma once
// The polygon mesh type. Faces keep their degree (triangles, quads, n-gons); nothing is
// triangulated. Points are Eigen vectors so geometry code needs no conversions.

// Order matters: EigenVectorT specializes OpenMesh's vector_traits for Eigen types, so it
// needs Eigen and vector_traits first, and must come before the mesh kernel.
#include "primo/util/types.h"
// clang-format off
#include <OpenMesh/Core/Utils/vector_traits.hh>
#include <OpenMesh/Core/Geometry/EigenVectorT.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
// clang-format on

namespace primo {

struct MeshTraits : OpenMesh::DefaultTraits {
  using Point = Vec3;
  using Normal = Vec3;
};

using Mesh = OpenMesh::PolyMesh_ArrayKernelT<MeshTraits>;

}  // namespace primo
