// The gauges ranked by their printability (docs/design.md, "Printability in the flow",
// "Re-ranking" and "Unread gauges rank last").
//
//   in:  per gauge, in the table's (geometric) order: its score, printed cd and failure code as
//        printability() gives them (NaN score and cd, no failure, for a gauge not simulated);
//   out: the order of the new ranking and each gauge's score in it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "linf/util/strided.hpp"

namespace linf::litho {

struct Ranking {
  std::vector<std::int32_t> order;  // the table's gauges, the new rank's first first
  std::vector<double> score;        // in the new order: the score; for an unread gauge the highest read one
  std::size_t read = 0;             // gauges measured, or failed at some condition
  double highest = 0;               // the greatest score (1 when none is read)
};

// A gauge is read when it has a printed cd or a failure; the read ones rank by score ascending
// (the worst printing first), ties by their order in the table; the others follow in the table's
// order, with the highest read score (1 when none is read), so that scores never decrease with
// rank. Throws std::invalid_argument for columns of different lengths or more than 2^31 - 1 gauges.
Ranking rank_by_printability(const Strided<double>& score, const Strided<double>& printed_cd,
                             const Strided<std::uint8_t>& fails);

}  // namespace linf::litho
