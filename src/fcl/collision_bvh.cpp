// Explicit instantiations: FCL's BVH-model-vs-shape and BVH-vs-BVH collision for
// QuadricSolver<double> (one piece of CollisionFunctionMatrix, see collision_pieces.h).
#define FCL_QUADRIC_INSTANTIATE_BVH
#include "fcl/collision_pieces.h"
