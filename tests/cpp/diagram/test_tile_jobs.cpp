// Tile jobs (tile_jobs.hpp, tiles.hpp build_tiled_jobs): the tiled pass planned here, each tile
// built alone from its job's bytes (as on another host), gives the local pass's parts bit for
// bit and in the same order, and the stream fed from them writes the same bytes; a job holds
// only its tile's sites; malformed bytes and a runner that drops tiles are refused. A sweep's
// tile task that classifies its pieces and reads their vertices (run_tile_job) gives the host's
// stretches bit for bit.
#include <gtest/gtest.h>

#include <any>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "diagram/tile_jobs.hpp"
#include "linf/diagram/builder.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/gauges/gauge.hpp"
#include "linf/geometry/sites.hpp"
#include "linf/pipeline/stream.hpp"
#include "linf/pipeline/tile_task.hpp"
#include "layouts.hpp"
#include "same_stretches.hpp"

using namespace linf;
using linf::testing::block;
using linf::testing::expect_same;

namespace {

// A part as bytes: its frame, then each piece's fields (not the padding).
std::string bytes_of(const std::vector<Piece>& part, const Box& frame) {
  std::string s(reinterpret_cast<const char*>(&frame), sizeof(Box));
  for (const Piece& p : part) {
    const double v[6] = {p.p.x, p.p.y, p.q.x, p.q.y, p.d1, p.d2};
    s.append(reinterpret_cast<const char*>(v), sizeof(v));
    const std::int32_t w[3] = {p.a, p.b, std::int32_t(p.kind)};
    s.append(reinterpret_cast<const char*>(w), sizeof(w));
  }
  return s;
}

std::vector<std::string> parts(const Sites& s, const Box& clip, const BuildOptions& o, const TileRunner& runner,
                               BuildStats* st = nullptr) {
  std::vector<std::string> out;
  build_parts(s, clip, o, st, [&](std::vector<Piece>& part, const Box& frame) { out.push_back(bytes_of(part, frame)); },
              runner);
  return out;
}

// Builds every job here, as a worker would from the bytes alone, with `threads` workers; keeps
// the jobs seen. task: as the cluster's workers do (run_tile_job: the job's preparation too),
// else the diagram's build_tile_job alone; `prepared` counts the results that carried one.
struct Inline {
  int threads = 1;
  std::vector<std::string> jobs;
  bool task = false;
  std::size_t prepared = 0;
  TileRunner runner() {
    return [this](const std::function<bool(std::string&)>& next, const std::function<void(std::string_view)>& done) {
      std::string job;
      while (next(job)) {
        jobs.push_back(job);
        const std::string copy(job);  // nothing shared with the planner
        const std::string result = task ? run_tile_job(copy, threads) : build_tile_job(copy, threads);
        prepared += !detail::decode_result(result).prepared.empty();
        done(result);
      }
    };
  }
};

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

std::string tmp(const std::string& name) {
  const char* d = std::getenv("TMPDIR");
  return std::string(d && *d ? d : "/tmp") + "/linf_test_tile_jobs_" + name;
}

}  // namespace

TEST(TileJobs, SamePartsInTheSameOrderAsTheLocalPass) {
  const linf::testing::Style styles[] = {linf::testing::Style::Rectilinear, linf::testing::Style::Octilinear,
                                         linf::testing::Style::AnyAngle};
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Sites s = sites_of_polygons(merge_polygons(block(seed, styles[seed % 3], 12, 10)));
    const Box clip = clip_box(s);
    const double side = std::max(clip.x2 - clip.x1, clip.y2 - clip.y1) / 3;
    for (double frac : {0.0, 0.3, 0.05}) {
      BuildOptions o;
      o.threads = 2;
      o.tile_size = frac * side;
      BuildStats st_local, st_jobs;
      const std::vector<std::string> local = parts(s, clip, o, {}, &st_local);
      for (int threads : {1, 2}) {
        Inline run{threads, {}};
        const std::vector<std::string> got = parts(s, clip, o, run.runner(), &st_jobs);
        const std::string at = "seed " + std::to_string(seed) + " tile " + std::to_string(o.tile_size) +
                               " worker threads " + std::to_string(threads);
        ASSERT_EQ(got.size(), local.size()) << at;
        for (std::size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(got[i] == local[i]) << at << ": part " << i;
        EXPECT_EQ(st_jobs.tiles, st_local.tiles) << at;
        EXPECT_EQ(st_jobs.tasks, st_local.tasks) << at;
        EXPECT_EQ(st_jobs.largest_tile_sites, st_local.largest_tile_sites) << at;
        EXPECT_EQ(st_jobs.raw_pieces, st_local.raw_pieces) << at;
        if (frac == 0.05) {
          ASSERT_GT(run.jobs.size(), 4u) << at;
          // A job holds its tile's sites (the halo's included), not the layer's: global ids
          // ascending, each with its own site.
          for (const std::string& bytes : run.jobs) {
            const detail::TileJob job = detail::decode_job(bytes);
            EXPECT_LT(job.sites.size(), s.sites.size() / 2) << at;
            for (std::size_t i = 0; i < job.ids.size(); ++i) {
              if (i) ASSERT_LT(job.ids[i - 1], job.ids[i]);
              const Site& g = s.sites[std::size_t(job.ids[i])];
              ASSERT_TRUE(job.sites[i].a == g.a && job.sites[i].b == g.b);
            }
          }
        }
      }
    }
  }
}

// The sweep's tiles as jobs (opt.sweep): each job carries the sites sweep_tiled gives its tile
// and is swept alone from its bytes, with the same parts in the same order as the local sweep,
// and the same counts.
TEST(TileJobs, SweepJobsGiveTheLocalSweepsParts) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Sites s = sites_of_polygons(merge_polygons(block(seed, linf::testing::Style::Rectilinear, 12, 10)));
    const Box clip = clip_box(s);
    const double side = std::max(clip.x2 - clip.x1, clip.y2 - clip.y1) / 3;
    for (double frac : {0.3, 0.05}) {
      BuildOptions o;
      o.sweep = true;
      o.threads = 2;
      o.tile_size = frac * side;
      BuildStats st_local, st_jobs;
      const std::vector<std::string> local = parts(s, clip, o, {}, &st_local);
      Inline run{1, {}};
      const std::vector<std::string> got = parts(s, clip, o, run.runner(), &st_jobs);
      const std::string at = "seed " + std::to_string(seed) + " tile " + std::to_string(o.tile_size);
      ASSERT_GT(run.jobs.size(), frac == 0.05 ? 4u : 1u) << at;
      ASSERT_EQ(got.size(), local.size()) << at;
      for (std::size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(got[i] == local[i]) << at << ": part " << i;
      EXPECT_EQ(st_jobs.tiles, st_local.tiles) << at;
      EXPECT_EQ(st_jobs.tasks, st_local.tasks) << at;
      EXPECT_EQ(st_jobs.largest_tile_sites, st_local.largest_tile_sites) << at;
      for (const std::string& bytes : run.jobs) {
        const detail::TileJob job = detail::decode_job(bytes);
        EXPECT_TRUE(job.opt.sweep) << at;
        EXPECT_TRUE(job.tasks.empty()) << at;
        EXPECT_LT(job.sites.size(), s.sites.size()) << at;
      }
    }
  }
}

// The sweep's jobs are planned ahead on the host's threads (util/ahead.hpp): the same jobs (sites,
// frames, the ring neighbours for the gauges' readings) in the same order for any number of them;
// a runner that fails mid-way stops the planners and its error reaches the caller.
TEST(TileJobs, PlannedAheadOnTheHostsThreadsTheSameJobs) {
  const Sites s = sites_of_polygons(merge_polygons(block(2, linf::testing::Style::Rectilinear, 12, 10)));
  const Box clip = clip_box(s);
  const double side = std::max(clip.x2 - clip.x1, clip.y2 - clip.y1) / 3;
  auto jobs = [&](int threads, const TileRunner& runner) {
    BuildOptions o;
    o.sweep = true;
    o.threads = threads;
    o.tile_size = 0.05 * side;
    build_parts(s, clip, o, nullptr, [](std::vector<Piece>&, const Box&) { return std::any{}; },
                [](std::vector<Piece>&, const Box&, std::any&) {}, runner, {}, kGaugeReadings);
  };
  Inline one{1, {}};
  jobs(1, one.runner());
  ASSERT_GT(one.jobs.size(), 20u);
  EXPECT_FALSE(detail::decode_job(one.jobs[0]).near_ids.empty() && detail::decode_job(one.jobs[1]).near_ids.empty());
  for (int threads : {2, 3, 5}) {
    Inline more{1, {}};
    jobs(threads, more.runner());
    ASSERT_EQ(more.jobs.size(), one.jobs.size()) << threads << " threads";
    // The contents, not the bytes: a job's options are the struct's bytes, padding included.
    for (std::size_t i = 0; i < one.jobs.size(); ++i) {
      const detail::TileJob x = detail::decode_job(more.jobs[i]), y = detail::decode_job(one.jobs[i]);
      const std::string at = std::to_string(threads) + " threads: job " + std::to_string(i);
      ASSERT_EQ(x.ids, y.ids) << at;
      ASSERT_EQ(x.near_ids, y.near_ids) << at;
      EXPECT_TRUE(x.frame.x1 == y.frame.x1 && x.frame.y1 == y.frame.y1 && x.frame.x2 == y.frame.x2 &&
                  x.frame.y2 == y.frame.y2) << at;
      EXPECT_EQ(x.prepare, kGaugeReadings) << at;
      EXPECT_EQ(x.opt.threads, threads) << at;
    }
    std::size_t built = 0;
    const TileRunner failing = [&](const std::function<bool(std::string&)>& next,
                                   const std::function<void(std::string_view)>& done) {
      for (std::string j; next(j);) {
        if (++built == 4) throw std::runtime_error("worker lost");
        done(build_tile_job(j, 1));
      }
    };
    try {
      jobs(threads, failing);
      ADD_FAILURE() << threads << " threads: the runner's error was lost";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "worker lost") << threads << " threads";
    }
  }
}

TEST(TileJobs, StreamFedByJobsWritesTheSameBytes) {
 for (const bool sweep : {false, true}) {
  // The subdivision on an octilinear block; the sweep (Manhattan layers) on a rectilinear one.
  const std::vector<Polygon> polys = block(4, sweep ? linf::testing::Style::Rectilinear : linf::testing::Style::Octilinear, 10, 8);
  DiagramOptions o;
  o.sweep = sweep;
  o.build.threads = 2;
  o.build.tile_size = 150;
  auto run = [&](const TileRunner& runner, const std::string& name, std::string& csv, std::string& gds,
                 bool on_tasks = false) {
    StreamOutputs so;
    so.csv = tmp(name + ".csv"), so.gds = tmp(name + ".gds"), so.dbu = 0.001;
    so.layers.layer = 7, so.layers.dbu = 0.001;
    so.keep = measurable_pair;
    so.keep_measurable = on_tasks;
    StreamResult r = stream_voronoi(polys, o, so, runner);
    EXPECT_TRUE(r.check.ok());
    csv = slurp(so.csv), gds = slurp(so.gds);
    std::remove(so.csv.c_str());
    std::remove(so.gds.c_str());
    return r;
  };
  std::string csv_local, gds_local;
  const StreamResult local = run({}, "local", csv_local, gds_local);
  ASSERT_GT(local.pieces, 1000u);
  EXPECT_EQ(local.diagram.swept, sweep);
  // The jobs prepared here; asked to prepare but built by the diagram alone (prepared here all
  // the same); prepared by their tasks (the sweep's only: the subdivision's are prepared here).
  for (const auto& [task, ask] : {std::pair{false, false}, std::pair{false, true}, std::pair{true, true}}) {
    SCOPED_TRACE(std::string(task ? "tasks" : "build_tile_job") + (ask ? ", asked to prepare" : ""));
    std::string csv_jobs, gds_jobs;
    Inline jobs{1, {}, task};
    const StreamResult got = run(jobs.runner(), "jobs", csv_jobs, gds_jobs, ask);
    ASSERT_GT(jobs.jobs.size(), 1u);
    EXPECT_EQ(jobs.prepared, task && sweep ? jobs.jobs.size() : 0u);
    EXPECT_EQ(got.pieces, local.pieces);
    EXPECT_EQ(got.counts, local.counts);
    EXPECT_EQ(got.diagram.tiles, local.diagram.tiles);
    EXPECT_TRUE(csv_jobs == csv_local) << "voronoi.csv differs";
    EXPECT_TRUE(gds_jobs == gds_local) << "the drawing differs";
    expect_same(local.stretches, got.stretches);
    EXPECT_EQ(got.diagram.swept, sweep);
  }
 }
}

TEST(TileJobs, MalformedBytesAndLostTilesAreRefused) {
  const Sites s = sites_of_polygons(merge_polygons(block(5, linf::testing::Style::Rectilinear, 6, 5)));
  const Box clip = clip_box(s);
  BuildOptions o;
  o.threads = 1;
  o.tile_size = 100;
  Inline keep{1, {}};
  parts(s, clip, o, keep.runner());
  ASSERT_GT(keep.jobs.size(), 1u);
  const std::string job = keep.jobs[0];
  EXPECT_THROW(build_tile_job("not a job", 1), std::invalid_argument);
  EXPECT_THROW(build_tile_job(job.substr(0, job.size() - 3), 1), std::invalid_argument);
  std::string other = job;
  other[sizeof(char[8])] ^= 1;  // the header's site size: another build of the core
  EXPECT_THROW(build_tile_job(other, 1), std::invalid_argument);
  // A runner that stops after one tile: no partial diagram.
  const TileRunner one = [](const std::function<bool(std::string&)>& next,
                            const std::function<void(std::string_view)>& done) {
    std::string j;
    if (next(j)) done(build_tile_job(j, 1));
  };
  EXPECT_THROW(parts(s, clip, o, one), std::runtime_error);
}
