// The streamed diagram stage (stream.hpp) gives what the in-memory stage gives: the same
// voronoi.csv and drawing byte for byte, the same counts, the same stretches and gauges, for
// every tile size; and a diagram that fails its check leaves no files behind.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include "linf/io/csv.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/gauges/gauge.hpp"
#include "linf/io/gds.hpp"
#include "linf/geometry/sites.hpp"
#include "linf/pipeline/stream.hpp"
#include "linf/gauges/stretch.hpp"
#include "layouts.hpp"

using namespace linf;

using linf::testing::block;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

bool exists(const std::string& path) { return std::ifstream(path).good(); }

// Every stretch field, as text: equal texts are equal stretches in equal order.
std::string dump(const Stretches& s) {
  std::ostringstream o;
  o.precision(17);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Stretch x = s[i];
    o << x.a << ' ' << x.b << ' ' << int(x.kind) << ' ' << x.length << ':';
    for (std::size_t k = 0; k < x.path.size(); ++k) o << ' ' << x.path[k].x << ',' << x.path[k].y << ',' << x.clearance[k];
    o << '\n';
  }
  return o.str();
}

struct Outputs {
  std::string csv, gds, stretches, gauges;
  std::size_t pieces = 0;
  DrawCounts counts{}, drawn{};
};

GdsLayers layers() {
  GdsLayers L;
  L.layer = 7;
  L.dbu = 0.001;
  return L;
}

Outputs in_memory(const std::vector<Polygon>& polys, const DiagramOptions& o, const std::string& dir) {
  Result r = voronoi_of_polygons(polys, o);
  EXPECT_TRUE(r.check.ok());
  Outputs out;
  out.pieces = r.diagram.pieces.size();
  for (const Piece& p : r.diagram.pieces) ++out.counts[std::size_t(p.kind)];
  write_pieces_csv(r.diagram, 0.001, dir + "_mem.csv");
  out.drawn = write_pieces_gds(r.diagram, layers(), dir + "_mem.gds");
  out.csv = slurp(dir + "_mem.csv"), out.gds = slurp(dir + "_mem.gds");
  std::remove((dir + "_mem.csv").c_str());
  std::remove((dir + "_mem.gds").c_str());
  out.stretches = dump(stretches_of(r.diagram, [&](std::int32_t a, std::int32_t b, PieceKind k) {
    return measurable_pair(r.diagram.sites, a, b, k);
  }));
  const Gauges g = gauges_of(r.diagram);
  write_gauges_csv(r.diagram.sites, g, 0.001, dir + "_mem_gauges.csv");
  out.gauges = slurp(dir + "_mem_gauges.csv");
  std::remove((dir + "_mem_gauges.csv").c_str());
  return out;
}

Outputs streamed(std::vector<Polygon> polys, const DiagramOptions& o, const std::string& dir) {
  StreamOutputs so;
  so.csv = dir + "_str.csv", so.gds = dir + "_str.gds", so.dbu = 0.001, so.layers = layers();
  so.keep = measurable_pair;
  StreamResult r = stream_voronoi(std::move(polys), o, so);
  EXPECT_TRUE(r.check.ok());
  EXPECT_GT(r.check.sampled_points, 0u);
  EXPECT_TRUE(r.diagram.pieces.empty());
  Outputs out;
  out.pieces = r.pieces, out.counts = r.counts, out.drawn = r.drawn;
  out.csv = slurp(so.csv), out.gds = slurp(so.gds);
  std::remove(so.csv.c_str());
  std::remove(so.gds.c_str());
  const Sites sites = r.diagram.sites;
  out.stretches = dump(r.stretches);
  const Gauges g = gauges_of(sites, std::move(r.stretches));
  write_gauges_csv(sites, g, 0.001, dir + "_str_gauges.csv");
  out.gauges = slurp(dir + "_str_gauges.csv");
  std::remove((dir + "_str_gauges.csv").c_str());
  return out;
}

std::string tmp(const std::string& name) {
  const char* d = std::getenv("TMPDIR");
  return std::string(d && *d ? d : "/tmp") + "/linf_test_stream_" + name;
}

}  // namespace

TEST(Stream, SameOutputsAsInMemoryForEveryTileSize) {
  const linf::testing::Style styles[] = {linf::testing::Style::Rectilinear, linf::testing::Style::Octilinear,
                                         linf::testing::Style::AnyAngle};
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const std::vector<Polygon> polys = block(seed, styles[seed % 3], 10, 8);
    DiagramOptions whole;
    whole.build.threads = 2;
    const Outputs ref = in_memory(polys, whole, tmp("ref"));
    ASSERT_GT(ref.pieces, 1000u);
    ASSERT_NE(ref.stretches.find('\n'), std::string::npos);
    for (double tile : {0.0, 600.0, 150.0}) {
      DiagramOptions o = whole;
      o.build.tile_size = tile;
      const Outputs got = streamed(polys, o, tmp("got"));
      const std::string at = "seed " + std::to_string(seed) + " tile " + std::to_string(tile);
      EXPECT_EQ(got.pieces, ref.pieces) << at;
      EXPECT_EQ(got.counts, ref.counts) << at;
      EXPECT_EQ(got.drawn, ref.drawn) << at;
      EXPECT_TRUE(got.csv == ref.csv) << at << ": voronoi.csv differs";
      EXPECT_TRUE(got.gds == ref.gds) << at << ": the drawing differs";
      EXPECT_TRUE(got.stretches == ref.stretches) << at << ": the stretches differ";
      EXPECT_TRUE(got.gauges == ref.gauges) << at << ": gauges.csv differs";
    }
  }
}

TEST(Stream, SweptTilesPreparedOnTheirThreadsGiveTheSameOutputs) {
  // The sweep's tiles are classified and their vertices read on the threads that swept them,
  // several at once (builder.hpp, PartPrepare): the outputs stay those of the in-memory stage
  // on the whole-layer sweep, bit for bit.
  for (std::uint64_t seed = 4; seed <= 6; ++seed) {
    const std::vector<Polygon> polys = block(seed, linf::testing::Style::Rectilinear, 12, 10);
    DiagramOptions whole;
    whole.sweep = true;
    whole.build.threads = 1;
    whole.build.tile_size = 0;
    const Outputs ref = in_memory(polys, whole, tmp("sref"));
    for (int threads : {1, 2, 3})
      for (double tile : {0.0, 600.0, 150.0}) {
        DiagramOptions o = whole;
        o.sweep = true;
        o.build.threads = threads;
        o.build.tile_size = tile;
        const Outputs got = streamed(polys, o, tmp("sgot"));
        const std::string at = "seed " + std::to_string(seed) + " tile " + std::to_string(tile) + " threads " +
                               std::to_string(threads);
        EXPECT_EQ(got.counts, ref.counts) << at;
        EXPECT_TRUE(got.csv == ref.csv) << at << ": voronoi.csv differs";
        EXPECT_TRUE(got.stretches == ref.stretches) << at << ": the stretches differ";
        EXPECT_TRUE(got.gauges == ref.gauges) << at << ": gauges.csv differs";
      }
  }
}

TEST(Stream, PointStretchesOfASquareViaAcrossTiles) {
  // Square vias: the centre, where the four corner bisectors meet, is the only place a via's
  // top and bottom edges are equally near (point stretches). Tiles cut through the centres.
  std::vector<Polygon> p;
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) p.push_back(linf::testing::box(100 * i, 100 * j, 100 * i + 40, 100 * j + 40));
  DiagramOptions whole;
  const Outputs ref = in_memory(p, whole, tmp("via_ref"));
  for (double tile : {0.0, 20.0, 35.0, 100.0}) {
    DiagramOptions o;
    o.build.tile_size = tile;
    const Outputs got = streamed(p, o, tmp("via_got"));
    EXPECT_TRUE(got.stretches == ref.stretches) << "tile " << tile;
    EXPECT_TRUE(got.gauges == ref.gauges) << "tile " << tile;
    EXPECT_TRUE(got.csv == ref.csv) << "tile " << tile;
  }
}

TEST(Stream, AFailedCheckLeavesNoFiles) {
  StreamOutputs so;
  so.csv = tmp("fail.csv"), so.gds = tmp("fail.gds");
  DiagramOptions o;
  o.checker.tolerance = 1e-300;  // nothing computed in floating point passes that
  EXPECT_THROW(stream_voronoi(block(4, linf::testing::Style::AnyAngle, 2, 2), o, so), DiagramError);
  EXPECT_FALSE(exists(so.csv));
  EXPECT_FALSE(exists(so.gds));
}

// After the tiles, the checker, the writers and the stretches take the joined pieces on a
// thread of their own (with more than one thread): an error there must reach the caller as
// it does on one thread, not end the process or leave it waiting. Here the stretches' filter
// fails once the pieces are being joined.
TEST(Stream, AnErrorWhileThePiecesAreTakenReachesTheCaller) {
  for (int threads : {1, 2}) {
    bool joining = false;
    std::size_t asked = 0;
    DiagramOptions o;
    o.build.threads = threads;
    o.progress = [&](const char* stage, std::size_t, std::size_t) {
      if (std::string(stage).find("joining") == 0) joining = true;
    };
    StreamOutputs so;
    so.csv = tmp("taken.csv");
    so.keep = [&](const Sites&, std::int32_t, std::int32_t, PieceKind) {
      if (joining && ++asked > 100) throw std::runtime_error("the filter failed");
      return true;
    };
    try {
      stream_voronoi(block(4, linf::testing::Style::Rectilinear, 2, 2), o, so);
      ADD_FAILURE() << "no error on " << threads << " thread(s)";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ("the filter failed", e.what()) << threads << " thread(s)";
    }
    EXPECT_GT(asked, 100u) << threads << " thread(s)";
    std::remove(so.csv.c_str());
  }
}
