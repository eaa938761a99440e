// The SOCS kernels: read from the ICCAD 2013 files as they are, their stated weights and
// norms, the copy the repository ships, their symmetry, and clear errors on bad files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>
#include <cstdlib>
#include <unistd.h>

#include "linf/litho/kernels.hpp"
#include "litho/litho_fixtures.hpp"

using namespace linf::litho;
using litho_test::exists;
using litho_test::shared;
using litho_test::shipped;

namespace {

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// scales.txt read as plain text, independently of read_kernels.
std::vector<double> numbers_of(const std::string& path) {
  std::istringstream in(bytes_of(path));
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

}  // namespace

// Both corners of the shared files: the count and the 24 weights of scales.txt, largest first,
// 35 x 35 entries, and each kernel of unit L2 norm (as the data's README states).
TEST(Kernels, SharedFilesReproduceTheirWeightsAndNorms) {
  for (const char* corner : {"M1OPC", "M1OPC_def"}) {
    if (!exists(shared(corner) + "/scales.txt")) GTEST_SKIP() << shared(corner) << " is missing (the shared data)";
    const Kernels k = read_kernels(shared(corner));
    const std::vector<double> stated = numbers_of(shared(corner) + "/scales.txt");
    ASSERT_EQ(stated.size(), 25u) << corner;
    ASSERT_EQ(stated[0], 24.0) << corner;
    ASSERT_EQ(k.count(), 24u) << corner;
    EXPECT_EQ(k.size, 35);
    EXPECT_EQ(k.half(), 17);
    EXPECT_EQ(k.period, 2048.0);
    for (std::size_t i = 0; i < 24; ++i) {
      EXPECT_EQ(k.weights[i], stated[i + 1]) << corner << " kernel " << i;
      if (i > 0) EXPECT_LE(k.weights[i], k.weights[i - 1]) << corner << " weights largest first";
      double norm2 = 0;
      for (const auto& v : k.values[i]) norm2 += std::norm(v);
      EXPECT_NEAR(std::sqrt(norm2), 1.0, 1e-6) << corner << " kernel " << i;
    }
  }
  // In focus the first weight is 86.943428 (the README's 86.94).
  if (exists(shared("M1OPC"))) EXPECT_EQ(read_kernels(shared("M1OPC")).weights[0], 86.943428);
}

// The iccad13 preset's files in models/ are the shared originals, byte for byte, with the licence.
TEST(Kernels, ShippedCopyIsTheOriginal) {
  if (!exists(shared("M1OPC"))) GTEST_SKIP() << shared("M1OPC") << " is missing (the shared data)";
  for (const char* corner : {"M1OPC", "M1OPC_def"}) {
    EXPECT_EQ(bytes_of(shipped(corner) + "/scales.txt"), bytes_of(shared(corner) + "/scales.txt"));
    for (int i = 0; i < 24; ++i) {
      const std::string f = "/fh" + std::to_string(i) + ".bin";
      const std::string a = bytes_of(shipped(corner) + f);
      EXPECT_EQ(a.size(), 9824u) << corner << f;
      EXPECT_TRUE(a == bytes_of(shared(corner) + f)) << corner << f;
    }
  }
  const std::string licence = std::string(LINF_REPO) + "/models/iccad13/LICENSE";
  EXPECT_EQ(bytes_of(licence), bytes_of(std::string(LINF_DATA) + "/openilt/LICENSE"));
  EXPECT_NE(bytes_of(licence).find("MIT License"), std::string::npos);
}

// A clear field images to sum_i w_i |K_i(0,0)|^2: 0.9536 in focus, 0.9508 defocused (not 1:
// the contest's threshold 0.225 is on this scale).
TEST(Kernels, ClearFieldValue) {
  EXPECT_NEAR(litho_test::focus().clear_field(), 0.953645, 1e-6);
  EXPECT_NEAR(read_kernels(shipped("M1OPC_def")).clear_field(), 0.950840, 1e-6);
  // Most of it is the first kernel's: 86.94 |K_0(0,0)|^2.
  const Kernels& k = litho_test::focus();
  EXPECT_GT(k.weights[0] * std::norm(k.at(0, 0, 0)), 0.9 * k.clear_field());
}

TEST(Kernels, SetIsSymmetricUnderTheSquaresTransforms) {
  const Kernels& k = litho_test::focus();
  const double defect = litho_test::tcc_symmetry_defect(k);
  double norm = 0;  // ||T||_F = sqrt(sum w_i^2) for orthonormal kernels
  for (double w : k.weights) norm += w * w;
  norm = std::sqrt(norm);
  std::printf("[ litho ] TCC symmetry defect (Frobenius, worst of the 8 transforms): %.3g, %.2g of ||T|| = %.4g\n",
              defect, defect / norm, norm);
  // The weights come in near pairs (35.418 / 35.407, 4.1438 / 4.1425, ...): x- and y-like
  // kernels. The defect is below 1e-3 of the TCC; the image tests rely on it being small.
  EXPECT_LT(defect, 1e-3 * norm);
  EXPECT_NEAR(k.weights[1], k.weights[2], 1e-3 * k.weights[1]);
  EXPECT_NEAR(k.weights[5], k.weights[6], 1e-3 * k.weights[5]);
}

// Bad files: std::invalid_argument with a sentence naming the file.
namespace {

struct Folder {
  std::string path;
  explicit Folder(const std::string& name) {
    const char* tmp = std::getenv("TMPDIR");
    path = std::string(tmp && *tmp ? tmp : "/tmp") + "/linf_litho_" + name + "_" + std::to_string(::getpid());
    std::system(("rm -rf '" + path + "' && mkdir -p '" + path + "' && cp " + shipped("M1OPC") + "/* '" + path + "'").c_str());
  }
  ~Folder() { std::system(("rm -rf '" + path + "'").c_str()); }
  void write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path + "/" + name, std::ios::binary) << bytes;
  }
};

std::string error_of(const std::string& folder) {
  try {
    read_kernels(folder);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Kernels, BadFilesGiveAClearError) {
  EXPECT_EQ(error_of("/nonexistent/kernels"), "kernel file /nonexistent/kernels/scales.txt: cannot be read");
  {
    Folder f("missing");
    std::remove((f.path + "/fh7.bin").c_str());
    EXPECT_EQ(error_of(f.path), "kernel file " + f.path + "/fh7.bin: cannot be read");
  }
  {
    Folder f("short");
    f.write("fh3.bin", bytes_of(shipped("M1OPC") + "/fh3.bin").substr(0, 9000));
    EXPECT_EQ(error_of(f.path), "kernel file " + f.path + "/fh3.bin: has 9000 bytes; its header (35 x 35) needs 9824");
  }
  {
    Folder f("header");
    std::string b = bytes_of(shipped("M1OPC") + "/fh0.bin");
    b[3] = 34;  // 34 x 35
    f.write("fh0.bin", b);
    EXPECT_EQ(error_of(f.path), "kernel file " + f.path +
                                    "/fh0.bin: has the header (34, 35, 2, ...); a kernel is n x n complex values, n odd: (n, n, 2, ...)");
  }
  {
    Folder f("count");
    f.write("scales.txt", "24\n1\n2\n");
    EXPECT_EQ(error_of(f.path), "kernel file " + f.path + "/scales.txt: says 24 kernels but lists 2 weights");
  }
  {
    Folder f("word");
    f.write("scales.txt", "2\n1.5\nabc\n");
    EXPECT_EQ(error_of(f.path), "kernel file " + f.path + "/scales.txt: 'abc' is not a number");
  }
  {
    Folder f("negative");
    f.write("scales.txt", "1\n-1.5\n");
    EXPECT_EQ(error_of(f.path), "kernel file " + f.path + "/scales.txt: holds a negative weight");
  }
  {
    Folder f("empty");
    f.write("scales.txt", "");
    EXPECT_NE(error_of(f.path).find("scales.txt: is empty"), std::string::npos);
  }
  // A folder with fewer weights than files reads only what scales.txt lists.
  {
    Folder f("fewer");
    f.write("scales.txt", "2\n3.0\n1.0\n");
    const Kernels k = read_kernels(f.path);
    EXPECT_EQ(k.count(), 2u);
    EXPECT_EQ(k.weights[1], 1.0);
  }
}
