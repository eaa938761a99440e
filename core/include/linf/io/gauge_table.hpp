// The gauge table: the ranked gauges as two row-major blocks of plain numbers, which the
// plugin reads in place (plugin/python/linf_opc/gauges.py). A Python object a gauge would be
// most of the flow's memory on a full layer; these are 132 bytes a gauge.
//
//   reals  float64 x10: x1, y1, x2, y2 (the measurement line), cx, cy (the gauge point), cd,
//          score, norm_score, tiebreak
//   ints   int32 x13: rank, teeth, site_a, site_b, a_x1, a_y1, a_x2, a_y2, b_x1, b_y1, b_x2,
//          b_y2, type index (GaugeType: internal, external, sandwich, comb, T)
//
// Written into the caller's memory, or into one file (the reals of every gauge, then the ints)
// that the caller maps instead of holding: a mapped file's pages are the kernel's to drop and
// read again. The file is written through buffers with pwrite, not a writable mapping, so that
// a full disk is an exception and not a SIGBUS.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "linf/gauges/gauge.hpp"

namespace linf {

constexpr std::size_t kGaugeReals = 10, kGaugeInts = 13;
constexpr std::size_t kGaugeRealBytes = kGaugeReals * sizeof(double);
constexpr std::size_t kGaugeIntBytes = kGaugeInts * sizeof(std::int32_t);

class GaugeTableWriter {
 public:
  // Into memory: `reals` holds count * kGaugeRealBytes, `ints` count * kGaugeIntBytes.
  GaugeTableWriter(std::size_t count, char* reals, char* ints);
  // Into `file`, created or truncated; throws std::runtime_error if it cannot be written.
  GaugeTableWriter(std::size_t count, const std::string& file);
  ~GaugeTableWriter();
  GaugeTableWriter(const GaugeTableWriter&) = delete;
  GaugeTableWriter& operator=(const GaugeTableWriter&) = delete;

  // The next gauge's row; its rank is the rows written before it plus one. Throws
  // std::range_error for an integer beyond 32 bits.
  void add(const Sites& sites, const Gauges& gauges, const Gauge& g);
  // The next n gauges' rows, as n calls of add, on `threads` threads (0: one a core): a row
  // depends on its gauge and rank alone, so the bytes do not depend on the threads.
  void add(const Sites& sites, const Gauges& gauges, const Gauge* g, std::size_t n, int threads);
  // Ends the file (nothing in memory); throws std::runtime_error on a write error.
  void close();

 private:
  void flush();
  void put(const char* p, std::size_t n, std::uint64_t at);

  std::size_t count_;
  std::string file_;
  int fd_ = -1;
  std::vector<char> buf_r_, buf_i_;  // a batch of rows on their way to the file
  char *rd_ = nullptr, *id_ = nullptr;
  std::size_t rows_ = 0, in_batch_ = 0, flushed_ = 0;
};

// Every gauge of `gauges` in rank order into `table`, which is closed after; each(g), if set,
// sees each gauge as it is written (then on one thread, in rank order; else the rows are made
// on `threads` threads, 0: one a core, with the same bytes). The gauges are consumed: their
// pages are given back as they are written (on a full layer the records are gigabytes, and
// nothing reads them afterwards), and gauges.gauges is empty after.
void write_gauge_table(const Sites& sites, Gauges& gauges, GaugeTableWriter& table,
                       const std::function<void(const Gauge&)>& each = {}, int threads = 1);

// A gauge table as the caller holds it, read in place.
struct GaugeTableView {
  const double* reals = nullptr;
  const std::int32_t* ints = nullptr;
  std::size_t count = 0;
};

// "#RANK TYPE CD", the CD in micrometres to 4 significant digits (as the plugin's
// gauge_output.label writes it with Python's "%.4g").
std::string gauge_label(std::int32_t rank, GaugeType type, double cd_um);

// The gauges as GDSII for the editor to read: each measurement line a zero-width path on
// layer/datatype, its gauge_label (cd times dbu) a text at the gauge point, in one cell.
// Throws std::out_of_range for a type index beyond GaugeType, std::runtime_error if the file
// cannot be written.
void write_gauges_gds(const GaugeTableView& table, const std::string& path, double dbu, int layer, int datatype,
                      const std::string& cell);

}  // namespace linf
