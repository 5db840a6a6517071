#ifndef FCL_SUPERELLIPSOID_SRC_FCL_GLUE_BVH_NODE_H
#define FCL_SUPERELLIPSOID_SRC_FCL_GLUE_BVH_NODE_H

// Internal: fcl::BVNodeBase's tree accessors, inline. libfcl compiles its own out of line, so
// each call is a call through the PLT; the BVH traversal makes several per node it visits, and
// on a large model they were a measurable part of its time. The encoding is fcl's
// (fcl/geometry/bvh/BV_node_base.h): first_child ≥ 0 indexes the left child, and the right
// child follows it; a leaf stores −(primitive index + 1). test_fcl_integration.cpp checks these
// against libfcl's accessors on every node of built models.

#include <fcl/geometry/bvh/BV_node_base.h>

namespace fcl_superellipsoid {
namespace detail {

inline bool isLeaf(const fcl::BVNodeBase& node) { return node.first_child < 0; }
inline int leftChild(const fcl::BVNodeBase& node) { return node.first_child; }
inline int rightChild(const fcl::BVNodeBase& node) { return node.first_child + 1; }
inline int primitiveId(const fcl::BVNodeBase& node) { return -(node.first_child + 1); }

}  // namespace detail
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SRC_FCL_GLUE_BVH_NODE_H
