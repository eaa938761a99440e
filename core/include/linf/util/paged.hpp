// Paged<T>: a growable array of plain values kept in a temporary file that the process maps.
//
// A full layer's whole-layer arrays (the sites, the gauges' stretches, the gauge records) are
// gigabytes. In anonymous memory the process must hold every page of them until it frees
// them; in a mapped file the pages are the kernel's: kept in memory while there is room,
// written out and dropped when there is not, read back when touched again. So the flow runs
// inside a memory limit smaller than its arrays (see docs/design.md, "Memory"), at the cost
// of disk traffic only when memory is short. The arrays are written and read mostly in order
// (by owner pair, which is by position on the layer), so a page once dropped is seldom needed
// again soon.
//
// Below kFileFrom bytes the array is plain anonymous memory (a small layout, the tests, the
// fuzzer: no file for each of thousands of tiny arrays); it moves into its file as it grows
// past that. The file lives in $TMPDIR (else /tmp) and is unlinked at once: it goes when the
// array does, also when the process dies. A reservation is address space and a sparse file;
// disk blocks are reserved (posix_fallocate) a chunk ahead of the values written, so a full
// disk is an exception, never a SIGBUS on a later write. Values are only ever written below
// size() (push_back, resize), which is what keeps that true. Only what std::vector's users
// here need: push_back, reserve, resize, indexing, contiguous data.
#pragma once
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace linf {

template <class T>
class Paged {
  static_assert(std::is_trivially_copyable_v<T>, "Paged holds plain values only");

 public:
  static constexpr std::size_t kFileFrom = std::size_t(16) << 20;
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  Paged() = default;
  ~Paged() { drop(); }
  Paged(const Paged& o) {
    resize(o.n_);
    if (o.n_) std::memcpy(static_cast<void*>(p_), o.p_, o.n_ * sizeof(T));
  }
  Paged& operator=(const Paged& o) {
    if (this != &o) *this = Paged(o);
    return *this;
  }
  Paged(Paged&& o) noexcept { take(o); }
  Paged& operator=(Paged&& o) noexcept {
    if (this != &o) {
      drop();
      take(o);
    }
    return *this;
  }

  std::size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  std::size_t capacity() const { return cap_; }
  T* data() { return p_; }
  const T* data() const { return p_; }
  T* begin() { return p_; }
  T* end() { return p_ + n_; }
  const T* begin() const { return p_; }
  const T* end() const { return p_ + n_; }
  T& operator[](std::size_t i) { return p_[i]; }
  const T& operator[](std::size_t i) const { return p_[i]; }
  T& back() { return p_[n_ - 1]; }
  const T& back() const { return p_[n_ - 1]; }

  void reserve(std::size_t n) {
    if (n > cap_) grow(n);
  }
  void push_back(const T& v) {
    if (n_ == cap_) grow(cap_ < 1024 ? 1024 : cap_ * 2);
    if (n_ == room_) make_room(n_ + 1);
    p_[n_++] = v;
  }
  // Grows to n values and leaves the new ones for the caller to write, every one of them before
  // any is read: several threads may then write parts at once, and fault their pages in side by
  // side (resize() would touch them all first, on one thread).
  void grow_unwritten(std::size_t n) {
    if (n <= n_) return;
    if (n > cap_) grow(n);
    if (n > room_) make_room(n);
    n_ = n;
  }
  // Shrinking gives the file's room and pages past the new size back; growing value-initialises.
  void resize(std::size_t n) {
    if (n > cap_) grow(n);
    if (n > room_) make_room(n);
    for (std::size_t i = n_; i < n; ++i) p_[i] = T();
    n_ = n;
    if (n < cap_ / 2) shrink();
  }
  void clear() { resize(0); }

 private:
  static constexpr std::size_t kChunk = std::size_t(64) << 20;  // disk reserved ahead, bytes

  static std::size_t page() { return std::size_t(sysconf(_SC_PAGESIZE)); }
  static std::size_t bytes_for(std::size_t n) {
    const std::size_t b = n * sizeof(T), pg = page();
    return (b + pg - 1) / pg * pg;
  }

  // Address space for `want` values: anonymous below kFileFrom, else the file's (sparse).
  void grow(std::size_t want) {
    const std::size_t bytes = bytes_for(want);
    if (fd_ < 0 && bytes < kFileFrom) {
      remap(bytes);
      room_ = cap_;
      return;
    }
    if (fd_ >= 0) {
      if (ftruncate(fd_, off_t(bytes)) != 0) fail("cannot grow a temporary file");
      remap(bytes);
      return;
    }
    // From anonymous memory into the file: what is there is written to it, then mapped from it.
    const std::size_t written = n_ * sizeof(T);
    const int fd = file_holding(p_, written);
    void* q = MAP_FAILED;
    if (ftruncate(fd, off_t(bytes)) == 0) q = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (q == MAP_FAILED) {
      const int e = errno;
      ::close(fd);
      fail("cannot map a temporary file", e);
    }
    if (p_) munmap(p_, bytes_);
    p_ = static_cast<T*>(q), fd_ = fd, bytes_ = bytes, cap_ = bytes / sizeof(T);
    room_bytes_ = std::min(bytes_, bytes_for(n_));  // pwrite gave the written part its blocks
    room_ = room_bytes_ / sizeof(T);
  }

  // Disk blocks for at least `n` values (and a chunk ahead), so that writing them cannot fail.
  void make_room(std::size_t n) {
    if (fd_ < 0) {
      room_ = cap_;
      return;
    }
    const std::size_t to = std::min(bytes_, bytes_for(n) + kChunk);
    const int e = posix_fallocate(fd_, off_t(room_bytes_), off_t(to - room_bytes_));
    if (e != 0)
      throw std::runtime_error("cannot make room for " + std::to_string(to >> 20) +
                               " MB in a temporary file (disk full?): " + std::strerror(e));
    room_bytes_ = to;
    room_ = to / sizeof(T);
  }

  void shrink() {
    const std::size_t bytes = bytes_for(n_ == 0 ? 1 : n_);
    if (bytes >= bytes_) return;
    remap(bytes);  // the mapping first, so that no page past the file's end stays mapped
    if (fd_ >= 0) {
      if (ftruncate(fd_, off_t(bytes)) != 0) fail("cannot shrink a temporary file");
      room_bytes_ = std::min(room_bytes_, bytes);
      room_ = room_bytes_ / sizeof(T);
    } else {
      room_ = cap_;
    }
  }

  void remap(std::size_t bytes) {
    void* q = p_ ? mremap(p_, bytes_, bytes, MREMAP_MAYMOVE)
                 : mmap(nullptr, bytes, PROT_READ | PROT_WRITE, fd_ >= 0 ? MAP_SHARED : MAP_PRIVATE | MAP_ANONYMOUS, fd_, 0);
    if (q == MAP_FAILED) throw std::bad_alloc();
    p_ = static_cast<T*>(q);
    bytes_ = bytes;
    cap_ = bytes / sizeof(T);
  }

  [[noreturn]] static void fail(const char* what, int e = errno) {
    throw std::runtime_error(std::string(what) + " (disk full?): " + std::strerror(e));
  }

  // A new unlinked temporary file holding `n` bytes from `data`.
  static int file_holding(const void* data, std::size_t n) {
    const char* env = std::getenv("TMPDIR");
    std::string name = std::string(env && *env ? env : "/tmp") + "/linf_opc_paged_XXXXXX";
    const int fd = mkostemp(name.data(), O_CLOEXEC);
    if (fd < 0) throw std::runtime_error("cannot create a temporary file " + name + ": " + std::strerror(errno));
    unlink(name.c_str());
    const char* from = static_cast<const char*>(data);
    off_t at = 0;
    while (n > 0) {
      const ssize_t k = pwrite(fd, from, n, at);
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0) {
        const int e = errno;
        ::close(fd);
        fail("cannot write a temporary file", e);
      }
      from += k, n -= std::size_t(k), at += k;
    }
    return fd;
  }

  void drop() {
    if (p_) munmap(p_, bytes_);
    if (fd_ >= 0) ::close(fd_);
    p_ = nullptr, fd_ = -1, n_ = cap_ = room_ = bytes_ = room_bytes_ = 0;
  }

  void take(Paged& o) {
    p_ = o.p_, fd_ = o.fd_, n_ = o.n_, cap_ = o.cap_, room_ = o.room_, bytes_ = o.bytes_, room_bytes_ = o.room_bytes_;
    o.p_ = nullptr, o.fd_ = -1, o.n_ = o.cap_ = o.room_ = o.bytes_ = o.room_bytes_ = 0;
  }

  T* p_ = nullptr;
  int fd_ = -1;
  std::size_t n_ = 0, cap_ = 0;
  std::size_t room_ = 0;  // values that have disk blocks (cap_ when anonymous)
  std::size_t bytes_ = 0, room_bytes_ = 0;
};

}  // namespace linf
