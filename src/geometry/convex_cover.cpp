// Convex cover of a composite quadric model: docs/algorithms.md section 12, convex_cover.h.
#include "fcl_quadric/geometry/convex_cover.h"

#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geometry/region_formula.h"

namespace fcl_quadric {

namespace {

using Conjunction = std::vector<int>;  // atom indices of the formula

struct PieceSet {
  std::vector<Conjunction> pieces;
  bool exact = true;
};

class CoverBuilder {
 public:
  CoverBuilder(const detail::Formula& f, const Box3& box) : f_(f), box_(box), convex_(f.atoms.size()) {
    for (std::size_t k = 0; k < f.atoms.size(); ++k)
      convex_[k] = ConvexSupport::fromRegion(QuadricRegion::atom(f.atoms[k]), box).has_value() ||
                   isEmptyPlane(f.atoms[k]);
  }

  PieceSet build(int n) const {
    const detail::Formula::Node& node = f_.nodes[n];
    PieceSet out;
    if (!node.is_and) {
      // A disjunction: the union of its children's pieces; a non-convex atom becomes the box.
      for (int a : node.atoms) {
        if (convex_[a]) {
          out.pieces.push_back({a});
        } else {
          out.pieces.push_back({});
          out.exact = false;
        }
      }
      for (int m : node.nodes) {
        PieceSet c = build(m);
        out.exact = out.exact && c.exact;
        for (auto& p : c.pieces) out.pieces.push_back(std::move(p));
      }
      if (static_cast<int>(out.pieces.size()) > tolerance_support::kMaxCoverPieces) return {{{}}, false};
      return out;
    }
    // A conjunction: its convex atoms, distributed over the pieces of each disjunctive child.
    Conjunction base;
    for (int a : node.atoms) {
      if (convex_[a]) base.push_back(a);
      else out.exact = false;
    }
    out.pieces.push_back(base);
    for (int m : node.nodes) {
      const PieceSet c = build(m);
      if (out.pieces.size() * c.pieces.size() > static_cast<std::size_t>(tolerance_support::kMaxCoverPieces)) {
        out.exact = false;  // dropped: the conjunction without this child is a superset
        continue;
      }
      out.exact = out.exact && c.exact;
      std::vector<Conjunction> next;
      for (const Conjunction& p : out.pieces)
        for (const Conjunction& q : c.pieces) {
          Conjunction r = p;
          r.insert(r.end(), q.begin(), q.end());
          next.push_back(std::move(r));
        }
      out.pieces = std::move(next);
    }
    return out;
  }

  /// The piece's convex support (one curved atom at most: later curved atoms are dropped, which
  /// clears `exact`); none when the piece is empty (an atom that excludes everything).
  std::optional<ConvexSupport> support(const Conjunction& piece, bool* exact) const {
    std::vector<QuadricRegion> parts;
    bool curved = false;
    for (int a : piece) {
      const bool is_curved = !detail::isPlanarAtom(f_.atoms[a]);
      if (is_curved && curved) {
        *exact = false;
        continue;
      }
      curved = curved || is_curved;
      parts.push_back(QuadricRegion::atom(f_.atoms[a]));
    }
    if (parts.empty()) return boxSupport();
    // Contains: a piece inside the model's box (a ball of a union) skips the box's faces; one
    // that reaches beyond it (a superset) keeps them (fromRegion checks which).
    return ConvexSupport::fromRegion(QuadricRegion::combine(QuadricRegion::Op::Intersection, std::move(parts)), box_,
                                     ConvexSupport::BoxRole::Contains);
  }

  ConvexSupport boxSupport() const {
    std::vector<Eigen::Vector3d> corners;
    for (int i = 0; i < 8; ++i)
      corners.emplace_back((i & 1) ? box_.hi[0] : box_.lo[0], (i & 2) ? box_.hi[1] : box_.lo[1],
                           (i & 4) ? box_.hi[2] : box_.lo[2]);
    return ConvexSupport::points(corners);
  }

 private:
  // A constant atom {c <= 0} with c > 0 is empty (convex); fromRegion reports it as none.
  static bool isEmptyPlane(const Eigen::Matrix4d& Q) {
    return Q.topLeftCorner<3, 3>().cwiseAbs().maxCoeff() == 0.0 && Q.topRightCorner<3, 1>().isZero() && Q(3, 3) > 0.0;
  }

  const detail::Formula& f_;
  Box3 box_;
  std::vector<bool> convex_;
};

}  // namespace

ConvexCover convexCover(const QuadricRegion& region, const Box3& box) {
  if (box.empty() || !box.lo.allFinite() || !box.hi.allFinite())
    throw std::invalid_argument("convexCover: the bounding box is empty or not finite");
  ConvexCover cover;
  if (std::optional<ConvexSupport> whole = ConvexSupport::fromRegion(region, box, ConvexSupport::BoxRole::Contains)) {
    cover.pieces.push_back(std::move(*whole));
    cover.exact = true;
    return cover;
  }
  const detail::Formula f(region);
  const CoverBuilder builder(f, box);
  PieceSet set = builder.build(f.root);
  cover.exact = set.exact;
  for (const Conjunction& piece : set.pieces)
    if (std::optional<ConvexSupport> s = builder.support(piece, &cover.exact)) cover.pieces.push_back(std::move(*s));
  if (cover.pieces.empty()) {  // every piece empty (a numerically empty model): the box, conservatively
    cover.pieces.push_back(builder.boxSupport());
    cover.exact = false;
  }
  return cover;
}

}  // namespace fcl_quadric
