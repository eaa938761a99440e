#include "tile_jobs.hpp"

#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include "linf/diagram/sweep.hpp"
#include "subdivision.hpp"
#include "util/parallel.hpp"

namespace linf::detail {

namespace {

// Format tags; the header also holds the structs' sizes, so that a job made by another build
// of the core is refused by name rather than misread.
constexpr char kJobTag[8] = {'L', 'I', 'N', 'F', 'J', 'O', 'B', '2'};
constexpr char kResultTag[8] = {'L', 'I', 'N', 'F', 'R', 'E', 'S', '2'};

struct Header {
  char tag[8] = {};
  std::uint32_t site = sizeof(Site), piece = sizeof(Piece), options = sizeof(BuildOptions),
                stats = sizeof(BuildStats);
};

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&v);
    out.append(p, sizeof(T));
  }
  template <class T>
  void put_all(const T* v, std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(std::uint64_t(n));
    out.append(reinterpret_cast<const char*>(v), n * sizeof(T));
  }
  std::string out;
};

class Reader {
 public:
  explicit Reader(std::string_view s) : s_(s) {}
  template <class T>
  T get() {
    T v;
    need(sizeof(T));
    std::memcpy(&v, s_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> get_all() {
    const std::uint64_t n = get<std::uint64_t>();
    if (n > (s_.size() - at_) / sizeof(T)) bad();
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), s_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
    return v;
  }
  // get_all<char>, straight into a string.
  std::string get_bytes() {
    const std::uint64_t n = get<std::uint64_t>();
    if (n > s_.size() - at_) bad();
    std::string v(s_.substr(at_, std::size_t(n)));
    at_ += std::size_t(n);
    return v;
  }
  void done() const {
    if (at_ != s_.size()) bad();
  }

 private:
  void need(std::size_t n) const {
    if (s_.size() - at_ < n) bad();
  }
  [[noreturn]] static void bad() { throw std::invalid_argument("a tile job's bytes are truncated or malformed"); }
  std::string_view s_;
  std::size_t at_ = 0;
};

void put_header(Writer& w, const char (&tag)[8]) {
  Header h;
  std::memcpy(h.tag, tag, 8);
  w.put(h);
}

void check_header(Reader& r, const char (&tag)[8], const char* what) {
  const Header h = r.get<Header>();
  const Header want;
  if (std::memcmp(h.tag, tag, 8) != 0)
    throw std::invalid_argument(std::string("not a tile ") + what + " of this core (wrong format tag)");
  if (h.site != want.site || h.piece != want.piece || h.options != want.options || h.stats != want.stats)
    throw std::invalid_argument(std::string("a tile ") + what +
                                " made by another build of the core: every host must run the same linf_opc_core");
}

}  // namespace

std::string encode_job(const TileJob& job) {
  Writer w;
  put_header(w, kJobTag);
  w.put(job.opt);
  w.put(job.origin);
  w.put(job.root);
  w.put(job.frame);
  w.put(job.tau);
  w.put_all(job.ids.data(), job.ids.size());
  w.put_all(job.sites.data(), job.sites.size());
  w.put_all(job.tasks.data(), job.tasks.size());
  std::vector<std::uint32_t> sizes;
  std::vector<int> flat;
  for (const auto& h : job.halos) sizes.push_back(std::uint32_t(h.size())), flat.insert(flat.end(), h.begin(), h.end());
  w.put_all(sizes.data(), sizes.size());
  w.put_all(flat.data(), flat.size());
  w.put(job.prepare);
  w.put_all(job.near_ids.data(), job.near_ids.size());
  w.put_all(job.near.data(), job.near.size());
  return std::move(w.out);
}

TileJob decode_job(std::string_view bytes) {
  Reader r(bytes);
  check_header(r, kJobTag, "job");
  TileJob job;
  job.opt = r.get<BuildOptions>();
  job.origin = r.get<Point>();
  job.root = r.get<Box>();
  job.frame = r.get<Box>();
  job.tau = r.get<double>();
  job.ids = r.get_all<int>();
  job.sites = r.get_all<Site>();
  job.tasks = r.get_all<Box>();
  const std::vector<std::uint32_t> sizes = r.get_all<std::uint32_t>();
  const std::vector<int> flat = r.get_all<int>();
  job.prepare = r.get<std::uint32_t>();
  job.near_ids = r.get_all<int>();
  job.near = r.get_all<Site>();
  r.done();
  if (job.sites.size() != job.ids.size() || sizes.size() != job.tasks.size() || job.near.size() != job.near_ids.size())
    throw std::invalid_argument("a tile job's parts do not agree");
  std::size_t at = 0;
  for (std::uint32_t n : sizes) {
    if (n > flat.size() - at) throw std::invalid_argument("a tile job's halos are truncated");
    job.halos.emplace_back(flat.begin() + std::ptrdiff_t(at), flat.begin() + std::ptrdiff_t(at + n));
    for (int t : job.halos.back())
      if (t < 0 || std::size_t(t) >= job.sites.size()) throw std::invalid_argument("a tile job's halo names no site of it");
    at += n;
  }
  if (at != flat.size()) throw std::invalid_argument("a tile job's halos do not agree");
  return job;
}

std::string encode_result(const TileResult& res) {
  Writer w;
  put_header(w, kResultTag);
  w.put(res.frame);
  w.put(res.stats);
  w.put_all(res.pieces.data(), res.pieces.size());
  w.put_all(res.prepared.data(), res.prepared.size());
  return std::move(w.out);
}

TileResult decode_result(std::string_view bytes) {
  Reader r(bytes);
  check_header(r, kResultTag, "result");
  TileResult res;
  res.frame = r.get<Box>();
  res.stats = r.get<BuildStats>();
  res.pieces = r.get_all<Piece>();
  res.prepared = r.get_bytes();
  r.done();
  return res;
}

TileResult build_job(const TileJob& job, int threads) {
  if (job.opt.sweep) {  // the sweep's tile: its sites swept inside the frame, in layout coordinates
    TileResult res;
    res.frame = job.frame;
    res.pieces = sweep_subset(job.sites, job.ids, job.frame);
    res.stats.tiles = 1;
    res.stats.largest_tile_sites = job.sites.size();
    return res;
  }
  // The model of the tile's sites alone, numbered 0..n-1 in global order, then told their
  // global ids: the same model, decisions and pieces as the local pass's over the whole list.
  SiteList own;
  own.reserve(job.sites.size());
  for (const Site& s : job.sites) own.push_back(s);
  std::vector<int> local(job.sites.size());
  for (std::size_t i = 0; i < local.size(); ++i) local[i] = int(i);
  BuildOptions opt = job.opt;
  opt.threads = threads;
  Model model(own, std::move(local), opt, job.tau, job.origin);
  model.global = job.ids;
  TileResult res;
  res.frame = job.frame;
  const std::size_t nw = worker_count(job.tasks.size(), threads);
  std::vector<Builder> workers(nw, Builder(model, job.root, nullptr));
  parallel_for(job.tasks.size(), threads, [&](unsigned w, std::size_t k) { workers[w].process(job.tasks[k], job.halos[k]); });
  collect(model, workers, res.stats, res.pieces);
  res.stats.tiles = 1;
  res.stats.tasks = job.tasks.size();
  res.stats.largest_tile_sites = job.sites.size();
  return res;
}

}  // namespace linf::detail

namespace linf {

std::string build_tile_job(std::string_view job, int threads) {
  return detail::encode_result(detail::build_job(detail::decode_job(job), threads));
}

}  // namespace linf
