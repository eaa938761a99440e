// The diagram and the gauges as CSV, in micrometres (the batch's voronoi.csv and gauges.csv).
//
//   voronoi.csv: kind,x1,y1,x2,y2,d1,d2,a_x1,a_y1,a_x2,a_y2,b_x1,b_y1,b_x2,b_y2
//                (a point site repeats its coordinates)
//   gauges.csv:  id,type,x1,y1,x2,y2,cx,cy,cd,score,norm_score,tiebreak,rank (id = rank)
//                [,context,count] (a plan's calibration_gauges.csv, verification_gauges.csv)
//   values: DBU times `dbu`, six decimals (norm_score as it is).
// Written here rather than row by row in Python: a large layer has millions of pieces and
// gauges. The same bytes as Python's csv module with "%.6f" (tested).
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "linf/gauges/gauge.hpp"
#include "linf/geometry/piece.hpp"
#include "linf/io/gauge_table.hpp"

namespace linf {

// x as printf's "%.6f" (and Python's) writes it, appended to `out`: the CSV files' numbers.
void append_fixed6(std::string& out, double x);

// Writes the file and its time into d.seconds_csv; throws std::runtime_error if it cannot.
void write_pieces_csv(Diagram& d, double dbu, const std::string& path);

// voronoi.csv written as the pieces come (a layer too large to hold them): the same bytes as
// write_pieces_csv for the same pieces in the same order.
class PiecesCsv {
 public:
  PiecesCsv(const std::string& path, double dbu);  // throws if the file cannot be written
  ~PiecesCsv();
  void add(const Sites& sites, const Piece* pieces, std::size_t n);
  void close();  // throws on a write error

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::vector<std::string> text_;  // a batch's lines, formatted chunk by chunk
  double dbu_;
};

// Gauges in rank order; throws std::runtime_error if the file cannot be written.
void write_gauges_csv(const Sites& sites, const Gauges& gauges, double dbu, const std::string& path);

// A plan's two extra columns, one value per row written: each gauge's context id (written as
// 16 hex digits) and the number of gauges of its type and context in the whole layer.
struct GaugeContexts {
  std::vector<std::uint64_t> ids, counts;
};

// Some rows of a gauge table, in the order of `rows` (indices into the table): a subset's
// gauges.csv (the per-pattern mode's, a split set's). Each line is the one write_gauges_csv
// writes for that gauge, its id and rank the gauge's rank in the whole table; with `contexts`,
// followed by ",context,count" (and the header by the two names). Throws std::out_of_range for a
// row or type index beyond the table, std::invalid_argument if `contexts` has not one value a
// row, std::runtime_error if the file cannot be written.
void write_gauges_csv_rows(const GaugeTableView& table, const std::vector<std::size_t>& rows, double dbu,
                           const std::string& path, const GaugeContexts* contexts = nullptr);

}  // namespace linf
