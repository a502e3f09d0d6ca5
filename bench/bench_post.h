/// The post-filter figures of `make bench` (bench/bench_post.cpp): every post filter's
/// production path on a rendered 1080p frame and an edge-dense one, checked bit for bit
/// against its reference implementation; the rescale and SSAA-resolve passes; each against a
/// plain read+write pass (the memory-bandwidth floor) at 1 and 2 threads.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "methods/method.h"

namespace aalab::bench {

/// The library scenes whose 1x 1920x1080 frames the post-filter figures and goals use: "real"
/// (the same frame since #28: 0.54 % of its pixels have a luma step ≥ 0.1 to the left or top
/// neighbour, aalab_bench_post) and "dense" (5.75 %).
inline constexpr const char* kRealFrameScene = "mesh";
inline constexpr const char* kDenseFrameScene = "checker-plane";

/// One 1080p input frame of the post-filter figures.
struct PostFrame {
  std::string key, desc;  ///< "real" / "dense", and the table's description
  Image8 img;
};

/// What the post-filter figures registered, for their table and goals.
struct PostBench {
  std::vector<PostFrame> frames;     ///< frames[0]: the mesh scene's 1x frame ("real")
  std::vector<std::string> filters;  ///< the post filters timed, in table order
};

/// Renders the frames, checks every optimised filter against its reference on both
/// (report["bit_identity"]; exits 2 on a difference) and registers the timed figures.
PostBench RegisterPostFigures(const Settings& cfg, Json& report);

/// The "## Post filters" section (post filters, rescale, SSAA resolve).
void PostTable(const PostBench& post, BenchOutput& out);

/// Goals: FXAA 3.11 p39 within 5× of the floor on real content (1 and 2 threads).
void PostFloorGoals(BenchOutput& out);

/// Goal: 2 threads ≥ 1.8× one thread for every post filter and frame.
void PostScalingGoal(const PostBench& post, BenchOutput& out);

}  // namespace aalab::bench
