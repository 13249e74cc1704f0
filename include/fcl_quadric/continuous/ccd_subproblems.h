#pragma once
/// \file ccd_subproblems.h
/// Subproblem identification for the continuous collision of two composite quadric models
/// (Choi 2008 thesis §6.2.1): every pair of boundary elements, one from each CQM, of the types
/// (F, F), (F, E), (E, F), (E, E), (F, V) and (V, F), minus the pairs the exclusion rules prove
/// useless, each tagged with the contact computation of §6.2.2 that solves it
/// (dimension_reduction_ccd.h).
///
/// Exclusion rules (§6.2.1), with the thesis's concave faces (Definition 6.1: a negative principal
/// curvature everywhere) split into concave (both curvatures <= 0) and saddle (FaceShape):
///  - F-F: a concave or planar face against a concave or planar face, and a saddle against a
///    concave or planar face. An isolated external contact needs the sum of the two faces'
///    curvature forms (outward normals, one frame) positive semidefinite; a concave or planar
///    face adds a form <= 0, which keeps the other's negative direction (concave: all of them;
///    saddle: one) negative. A planar face is bounded by edges, so a plane-plane contact is found
///    by the plane against the other face's boundary curves. Saddle against saddle is NOT
///    excluded, though both are concave by Definition 6.1 and §6.2.1 excludes the pair: with
///    crossed concave directions their forms can sum to a positive definite one, and two
///    hourglasses touch first at such a point (docs/reliability.md finding 53).
///  - F-E: a concave face against a concave edge. A saddle face is not excluded against a
///    concave edge: along the edge its normal curvature may be positive.
/// Pure algebra over the boundary elements of geometry/quadric_region.h: std + Eigen only.

#include <string>
#include <vector>

#include "fcl_quadric/geometry/quadric_region.h"

namespace fcl_quadric {

/// The dimension of a boundary element. Apex: the apex of a cone face (the singular point of its
/// quadric), not one of the boundary elements of thesis §6.1 but a point contact of its own; its
/// index is the face's (dimension_reduction_ccd.h adds its face-vertex subproblems).
enum class ElementKind { Face, Edge, Vertex, Apex };

/// The contact computation of §6.2.2 that a pair of extended boundary elements needs, named
/// <element of one body><element of the other> with "Quadric" a curved face, "Plane" a planar
/// face, "Conic" / "Line" the edge kinds, "Vertex" a vertex, "Curve" a quartic edge (two curved
/// faces meeting: thesis §6.5, outside the conic-edge class the chapter solves).
enum class SubproblemType {
  QuadricQuadric,  ///< F-F: subresultant sequence of the characteristic polynomial in t
  QuadricPlane,    ///< F-F: the plane as the degenerate quadric P P^T
  QuadricConic,    ///< F-E: reduced to two conics in the conic's plane
  QuadricLine,     ///< F-E: direct substitution, discriminant of the quadratic in s
  PlaneConic,      ///< F-E: the line plane ∩ conic plane against the conic
  PlaneLine,       ///< F-E: the line lying on the plane (common roots of two polynomials)
  FaceVertex,      ///< F-V: direct substitution of the vertex
  ConicConic,      ///< E-E: reduced to intervals on the line of the two conic planes (1D)
  ConicLine,       ///< E-E: direct substitution of the line's point in the conic's plane
  LineLine,        ///< E-E: coplanarity of the two lines
  Curve,           ///< a quartic edge is involved (thesis §6.5): no algebraic computation here
};
const char* toString(SubproblemType t);

/// One CCD subproblem: element (kind_a, index_a) of body a against element (kind_b, index_b)
/// of body b; indices into the BoundaryElements lists (faces / edges / vertices).
struct CcdSubproblem {
  ElementKind kind_a = ElementKind::Face;
  int index_a = 0;
  ElementKind kind_b = ElementKind::Face;
  int index_b = 0;
  SubproblemType type = SubproblemType::QuadricQuadric;
};

/// "F<i>", "E<i>", "V<i>" (the labels of boundaryElementLabel in region_ccd.h); "A<i>" for the
/// apex of cone face i. No failure mode.
std::string elementLabel(ElementKind kind, int index);

/// All subproblems of §6.2.1 for two CQMs with boundary elements `a` and `b`, with the exclusion
/// rules applied: F-F, F-E, E-F, E-E, F-V, V-F, in that order (within each, a's index major).
/// No failure mode: indices inside the lists are taken as given.
std::vector<CcdSubproblem> identifySubproblems(const BoundaryElements& a, const BoundaryElements& b);

}  // namespace fcl_quadric
