#include "linf/csv.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

namespace linf {

void write_pieces_csv(Diagram& d, double dbu, const std::string& path) {
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) throw std::runtime_error("cannot write " + path);
  std::fputs("kind,x1,y1,x2,y2,d1,d2,a_x1,a_y1,a_x2,a_y2,b_x1,b_y1,b_x2,b_y2\r\n", f.get());
  const auto& S = d.sites.sites;
  for (const Piece& p : d.pieces) {
    const Site& a = S[p.a];
    const Site& b = S[p.b];
    const double v[14] = {p.p.x, p.p.y, p.q.x, p.q.y, p.d1, p.d2,
                          double(a.a.x), double(a.a.y), double(a.b.x), double(a.b.y),
                          double(b.a.x), double(b.a.y), double(b.b.x), double(b.b.y)};
    std::fputs(kind_name(p.kind), f.get());
    for (double x : v) {
      // The same text as Python's "%.6f" % (x * dbu): printf rounds the same binary value.
      std::fprintf(f.get(), ",%.6f", x * dbu);
    }
    std::fputs("\r\n", f.get());
  }
  if (std::ferror(f.get())) throw std::runtime_error("error writing " + path);
  d.seconds_csv = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace linf
