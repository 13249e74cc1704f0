// Explicit instantiations: FCL's OcTree collision functions for QuadricSolver<double> (one piece
// of CollisionFunctionMatrix, see collision_pieces.h). Empty when FCL is built without OctoMap.
#define FCL_QUADRIC_INSTANTIATE_OCTREE
#include "fcl/collision_pieces.h"
