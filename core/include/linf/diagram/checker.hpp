// The independent checker. It shares no code with the builder: distances come from
// distance.hpp (minimum over breakpoints), neighbours from its own BoxTree of the sites (util/box_tree.hpp).
//
// 1. Every piece, sampled at its ends and inside: both owners at the same distance and the
//    stated clearances at the ends; and no site of the diagram strictly closer, on every piece
//    (a full check) or on one piece in CheckOptions::search_every, chosen by a hash of the piece
//    (that search is most of a full check's cost: docs/design.md, "The checker").
// 2. Random pairs of nearby points whose owners differ (by the ownership rule, see
//    builder.hpp; pairs too close to a near-tie are skipped): some piece crosses
//    the segment between them (no Voronoi edge is missing), and where one piece alone crosses
//    it, that piece's owners are the two points' (a piece along a line where a third site ties
//    with both is not labelled with the third).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "linf/geometry/piece.hpp"

namespace linf {

constexpr int kMostSamples = 16;

struct CheckOptions {
  int samples_per_piece = 3;   // 2 to kMostSamples: the two ends, plus evenly spaced interior points
  int crossing_pairs = 2000;   // random pairs for the completeness test
  double pair_step = 2.0;      // DBU between the two points of a pair
  std::uint64_t seed = 1;
  double tolerance = 0;        // DBU; 0 picks 1e-6 + 1e-9 * coordinate scale
  int threads = 0;             // threads sampling the pieces; 0: one per core
  int search_every = 1;        // 1: every piece searched for a closer site (full); n: one in n
};

// The pipeline's default, a sampled check (the batch's and the editor's -rd check=sample): one
// piece in 16 searched for a closer site, every piece's owners and clearances tested, all pairs.
constexpr int kSampledSearchEvery = 16;

struct CheckReport {
  std::size_t sampled_points = 0, searched_pieces = 0, pairs_tested = 0, pairs_separated = 0;
  std::size_t equidistance_errors = 0, clearance_errors = 0, closer_site_errors = 0, missing_edge_errors = 0;
  std::size_t wrong_owner_errors = 0;
  double worst_error = 0;             // DBU, over all distance tests
  std::vector<std::string> messages;  // the first few failures, with coordinates
  bool ok() const {
    return equidistance_errors + clearance_errors + closer_site_errors + missing_edge_errors + wrong_owner_errors == 0;
  }
};

CheckReport check_diagram(const Diagram& d, const CheckOptions& opt = {});

// The same check over pieces that come in batches (a layer too large to hold its pieces): the
// pairs are drawn from the sites when it is made, each batch is sampled and marks the pairs its
// pieces cross, finish() reports the pairs that no piece crossed, or one piece of other owners.
// typical_clearance: how far from a site half the pairs are drawn (check_diagram: the median
// clearance of the pieces).
class Checker {
 public:
  Checker(const Sites& sites, const Box& clip, double typical_clearance, const CheckOptions& opt = {});
  ~Checker();
  void add(const Piece* pieces, std::size_t n);
  CheckReport finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The median of a sample of clearances (1 if there is none), and that of the clearances at the
// start of about a thousand of the pieces.
double median_clearance(std::vector<double> sample);
double typical_clearance(const std::vector<Piece>& pieces);

}  // namespace linf
