// live_scalpel: the time-critical cut of paper section 5 from C++17, driven the way a
// surgery simulation would drive it. The Multi-Tessellation of the mesh given is built and
// a live model made at a middle resolution; the body is bent (the simulation's deformed
// positions, set with mtcut_live_set_positions) and a scalpel crosses it in 12 time
// steps. Each step cuts what the blade swept from the current mesh first, where the body
// lies now, and queues the cut of the model (mtcut_live_scalpel_sweep, given the blade at
// the step's start and end); every other step goes on with that queue within a budget
// (mtcut_live_process_pending); what is left is processed at the end. The current mesh
// must be valid after every step, every queued cut taken, and the body in two pieces at
// the end, in the current mesh and in the model. Writes live-scalpel.vtu (the last
// current mesh) with its JSON sidecar. Exit 1 on the first surprise.
//
// Usage: live_scalpel MESH_FILE OUTPUT_DIR
#include <mtcut.h>

#include "handles.hpp"
#include "sidecar.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace mtcut_example;

// The blade at step k of `steps`: a segment spanning the body's height (with margin),
// leaning a little in y, moved across it in x (from outside to outside).
std::vector<double> blade(const double lo[3], const double hi[3], int k, int steps) {
  const double d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  const double x = lo[0] - 0.02 * d[0] + 1.04 * d[0] * k / steps;
  const double y = 0.5 * (lo[1] + hi[1]);
  return {x, y + 0.013 * d[1], lo[2] - 0.1 * d[2], x, y - 0.011 * d[1], hi[2] + 0.1 * d[2]};
}

// The queued model work, within `max_fragments` (0: all of it).
mtcut_pending_report process_pending(mtcut_live *live, size_t max_fragments) {
  mtcut_pending_report report;
  std::memset(&report, 0, sizeof report);
  report.struct_size = sizeof report;
  check(mtcut_live_process_pending(live, max_fragments, 0.0, &report), "queued work");
  return report;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: live_scalpel MESH_FILE OUTPUT_DIR\n");
    return 2;
  }
  try {
    mtcut_mesh *raw_mesh = nullptr;
    check(mtcut_mesh_read(argv[1], &raw_mesh), "read");
    Mesh input(raw_mesh);
    double lo[3], hi[3];
    check(mtcut_mesh_bounding_box(input.get(), lo, hi), "bounding box");
    mtcut_mt *raw_mt = nullptr;
    check(mtcut_mt_build(input.get(), nullptr, &raw_mt), "build");
    Mt mt(raw_mt);
    const mtcut_mt_stats st = statistics(mt.get());

    // The simulation's mesh: the model at a middle error, kept up to date by the cuts.
    mtcut_extract_options resolution;
    resolution.struct_size = sizeof resolution;
    check(mtcut_extract_options_default(&resolution), "extract options");
    resolution.threshold = std::sqrt(st.min_error * st.max_error);
    mtcut_live *raw_live = nullptr;
    check(mtcut_live_new(mt.get(), &resolution, &raw_live), "live model");
    Live live(raw_live);
    const size_t n = mtcut_live_vertex_count(live.get());
    std::printf("model: %zu fragments; current mesh: %zu tets, %zu vertices\n", st.fragments,
                mtcut_live_tet_count(live.get()), n);

    // The body bent by the simulation (0.5% of its diagonal, no tet inverted), set as the
    // current positions; the model keeps the rest positions.
    std::vector<double> xyz(3 * n);
    check(mtcut_live_copy_rest_positions(live.get(), xyz.data(), n), "rest positions");
    const double diag =
        std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                  (hi[2] - lo[2]) * (hi[2] - lo[2]));
    const double k = 2.0 * M_PI / diag;
    for (size_t v = 0; v < n; v++) {
      double *p = &xyz[3 * v];
      const double x = p[0], y = p[1];
      p[0] += 0.005 * diag * std::sin(k * y);
      p[2] += 0.005 * diag * std::cos(k * x);
    }
    check(mtcut_live_set_positions(live.get(), xyz.data(), n), "bend");

    // The scalpel: each step cuts what the blade swept, frontier first, then a budget of
    // the queued model work.
    const int steps = 12;
    size_t refused = 0, fragments = 0;
    double slowest_ms = 0.0;
    for (int s = 1; s <= steps; s++) {
      const std::vector<double> from = blade(lo, hi, s - 1, steps), to = blade(lo, hi, s, steps);
      mtcut_cut_stats stats;
      std::memset(&stats, 0, sizeof stats);
      stats.struct_size = sizeof stats;
      const auto start = std::chrono::steady_clock::now();
      check(mtcut_live_scalpel_sweep(live.get(), from.data(), to.data(), &stats), "frontier cut");
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      slowest_ms = std::fmax(slowest_ms, ms);
      // Time for some of the queued work every other frame: a budget of one fragment
      // starts one queued cut (a cut is processed whole), so the queue grows meanwhile.
      if (s % 2 == 0) {
        const mtcut_pending_report report = process_pending(live.get(), 1);
        refused += report.refused;
        fragments += report.fragments;
        verify(report.cuts_done == 1, "the budget starts one cut");
      }
      std::printf("step %2d: %4zu current tets cut in %.3f ms; %zu model cut(s) queued\n", s,
                  stats.tets_cut, ms, mtcut_live_pending_cuts(live.get()));
      mtcut_mesh *raw = nullptr;
      check(mtcut_live_mesh(live.get(), &raw), "current mesh");
      Mesh current(raw);
      verify_valid(current.get(), "current mesh at step " + std::to_string(s));
    }
    const mtcut_pending_report report = process_pending(live.get(), 0);
    refused += report.refused;
    fragments += report.fragments;
    verify(mtcut_live_pending_cuts(live.get()) == 0, "nothing left queued");
    verify(refused == 0, "every queued cut taken");

    mtcut_mesh *raw = nullptr;
    check(mtcut_live_mesh(live.get(), &raw), "current mesh");
    Mesh current(raw);
    verify_valid(current.get(), "current mesh at the end");
    verify(components(current.get()) == 2, "the current mesh is in two pieces");
    // The host maps its FEM state by model vertex: one id per current vertex.
    std::vector<uint32_t> ids(mtcut_live_vertex_count(live.get()));
    check(mtcut_live_copy_mt_vertex_ids(live.get(), ids.data(), ids.size()), "vertex ids");
    mtcut_mt *raw_cut = nullptr;
    check(mtcut_live_mt(live.get(), &raw_cut), "the cut model");
    Mt cut_model(raw_cut);
    bool valid = false;
    check(mtcut_mt_validate(cut_model.get(), &valid, nullptr, 0, nullptr), "model validation");
    verify(valid, "the cut model is valid");
    verify(statistics(cut_model.get()).components == 2, "the model is two models");
    std::printf("done: slowest frontier-first step %.3f ms, %zu fragments of queued work; "
                "current mesh %zu tets in 2 pieces, model in 2 components\n",
                slowest_ms, fragments, mtcut_mesh_tet_count(current.get()));
    mtcut_example_write_vtu(current.get(), argv[2], "live-scalpel.vtu");
  } catch (const std::exception &e) {
    std::fprintf(stderr, "live_scalpel: %s\n", e.what());
    return 1;
  }
  return 0;
}
