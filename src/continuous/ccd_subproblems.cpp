// Subproblem identification with the exclusion rules of thesis §6.2.1 (ccd_subproblems.h).
#include "fcl_quadric/continuous/ccd_subproblems.h"

namespace fcl_quadric {

const char* toString(SubproblemType t) {
  switch (t) {
    case SubproblemType::QuadricQuadric: return "quadric-quadric";
    case SubproblemType::QuadricPlane: return "quadric-plane";
    case SubproblemType::QuadricConic: return "quadric-conic";
    case SubproblemType::QuadricLine: return "quadric-line";
    case SubproblemType::PlaneConic: return "plane-conic";
    case SubproblemType::PlaneLine: return "plane-line";
    case SubproblemType::FaceVertex: return "face-vertex";
    case SubproblemType::ConicConic: return "conic-conic";
    case SubproblemType::ConicLine: return "conic-line";
    case SubproblemType::LineLine: return "line-line";
    case SubproblemType::Curve: return "curve";
  }
  return "?";
}

std::string elementLabel(ElementKind kind, int index) {
  const char c = kind == ElementKind::Face   ? 'F'
                 : kind == ElementKind::Edge ? 'E'
                 : kind == ElementKind::Apex ? 'A'
                                             : 'V';
  return std::string(1, c) + std::to_string(index);
}

namespace {

SubproblemType faceFace(const BoundaryFace& f, const BoundaryFace& g) {
  return (f.planar() || g.planar()) ? SubproblemType::QuadricPlane : SubproblemType::QuadricQuadric;
}

SubproblemType faceEdge(const BoundaryFace& f, const BoundaryEdge& e) {
  switch (e.kind) {
    case EdgeKind::Curve: return SubproblemType::Curve;
    case EdgeKind::Conic: return f.planar() ? SubproblemType::PlaneConic : SubproblemType::QuadricConic;
    case EdgeKind::Line: return f.planar() ? SubproblemType::PlaneLine : SubproblemType::QuadricLine;
  }
  return SubproblemType::Curve;
}

SubproblemType edgeEdge(const BoundaryEdge& e, const BoundaryEdge& g) {
  if (e.kind == EdgeKind::Curve || g.kind == EdgeKind::Curve) return SubproblemType::Curve;
  if (e.kind == EdgeKind::Conic && g.kind == EdgeKind::Conic) return SubproblemType::ConicConic;
  if (e.kind == EdgeKind::Line && g.kind == EdgeKind::Line) return SubproblemType::LineLine;
  return SubproblemType::ConicLine;
}

// §6.2.1 exclusion rules, saddles apart (ccd_subproblems.h).
bool excludedFaceFace(const BoundaryFace& f, const BoundaryFace& g) {
  const bool f_flat_or_in = f.concave() || f.planar(), g_flat_or_in = g.concave() || g.planar();
  return (f_flat_or_in || f.saddle()) && (g_flat_or_in || g.saddle()) && !(f.saddle() && g.saddle());
}
bool excludedFaceEdge(const BoundaryFace& f, const BoundaryEdge& e) { return f.concave() && e.concave; }

}  // namespace

std::vector<CcdSubproblem> identifySubproblems(const BoundaryElements& a, const BoundaryElements& b) {
  using K = ElementKind;
  std::vector<CcdSubproblem> out;
  const int fa = static_cast<int>(a.faces.size()), fb = static_cast<int>(b.faces.size());
  const int ea = static_cast<int>(a.edges.size()), eb = static_cast<int>(b.edges.size());
  const int va = static_cast<int>(a.vertices.size()), vb = static_cast<int>(b.vertices.size());
  for (int i = 0; i < fa; ++i)
    for (int j = 0; j < fb; ++j)
      if (!excludedFaceFace(a.faces[i], b.faces[j])) out.push_back({K::Face, i, K::Face, j, faceFace(a.faces[i], b.faces[j])});
  for (int i = 0; i < fa; ++i)
    for (int j = 0; j < eb; ++j)
      if (!excludedFaceEdge(a.faces[i], b.edges[j])) out.push_back({K::Face, i, K::Edge, j, faceEdge(a.faces[i], b.edges[j])});
  for (int i = 0; i < ea; ++i)
    for (int j = 0; j < fb; ++j)
      if (!excludedFaceEdge(b.faces[j], a.edges[i])) out.push_back({K::Edge, i, K::Face, j, faceEdge(b.faces[j], a.edges[i])});
  for (int i = 0; i < ea; ++i)
    for (int j = 0; j < eb; ++j) out.push_back({K::Edge, i, K::Edge, j, edgeEdge(a.edges[i], b.edges[j])});
  for (int i = 0; i < fa; ++i)
    for (int j = 0; j < vb; ++j) out.push_back({K::Face, i, K::Vertex, j, SubproblemType::FaceVertex});
  for (int i = 0; i < va; ++i)
    for (int j = 0; j < fb; ++j) out.push_back({K::Vertex, i, K::Face, j, SubproblemType::FaceVertex});
  return out;
}

}  // namespace fcl_quadric
