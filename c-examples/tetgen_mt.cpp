// tetgen_mt: TetGen and mtcut together, in C++17. TetGen (libtet, -DTETLIBRARY)
// tetrahedralizes a built-in closed surface, a 4 x 4 x 2 box with a square 1 x 1 hole
// through it (volume 30); mtcut builds its Multi-Tessellation (reporting progress), saves
// and reloads it, extracts it at two error thresholds and with a focus region kept up to
// date by a frontier, cuts the finest extraction right through, and writes .vtu files with
// their JSON sidecars (see sidecar.h): tetgen-coarse.vtu (an extraction), tetgen-focus.vtu
// (the frontier's mesh) and tetgen-cut.vtu (the cut); it also makes the model of the half
// x < 2 (a region of interest) and cuts the model itself. Every result is checked; exit 1
// on the first surprise.
//
// Usage: tetgen_mt OUTPUT_DIR
#include <mtcut.h>

#include "handles.hpp"
#include "sidecar.h"

#include <tetgen.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace mtcut_example;

// One facet of the surface: an outer polygon, and optionally an inner one cut out of it.
void set_facet(tetgenio::facet &f, const std::vector<int> &outer, const std::vector<int> &inner,
               const double *hole) {
  tetgenio::init(&f);
  f.numberofpolygons = inner.empty() ? 1 : 2;
  f.polygonlist = new tetgenio::polygon[f.numberofpolygons];
  const std::vector<int> *loops[2] = {&outer, &inner};
  for (int p = 0; p < f.numberofpolygons; p++) {
    tetgenio::polygon &poly = f.polygonlist[p];
    tetgenio::init(&poly);
    poly.numberofvertices = static_cast<int>(loops[p]->size());
    poly.vertexlist = new int[poly.numberofvertices];
    std::memcpy(poly.vertexlist, loops[p]->data(), loops[p]->size() * sizeof(int));
  }
  if (hole != nullptr) {
    f.numberofholes = 1;
    f.holelist = new double[3]{hole[0], hole[1], hole[2]};
  }
}

// TetGen's quality mesh of the box with a hole: points 0-7 the outer box (bottom, then
// top), 8-15 the hole's square (bottom, then top).
Mesh tetrahedralize_box_with_hole() {
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = 16;
  in.pointlist = new double[3 * 16];
  const double outer[4][2] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  const double inner[4][2] = {{1.5, 1.5}, {2.5, 1.5}, {2.5, 2.5}, {1.5, 2.5}};
  for (int level = 0; level < 2; level++) {
    for (int k = 0; k < 4; k++) {
      double *p = &in.pointlist[3 * (4 * level + k)];
      p[0] = outer[k][0], p[1] = outer[k][1], p[2] = 2.0 * level;
      double *q = &in.pointlist[3 * (8 + 4 * level + k)];
      q[0] = inner[k][0], q[1] = inner[k][1], q[2] = 2.0 * level;
    }
  }
  in.numberoffacets = 10;
  in.facetlist = new tetgenio::facet[10];
  const double hole_bottom[3] = {2, 2, 0}, hole_top[3] = {2, 2, 2};
  set_facet(in.facetlist[0], {0, 1, 2, 3}, {8, 9, 10, 11}, hole_bottom);
  set_facet(in.facetlist[1], {4, 5, 6, 7}, {12, 13, 14, 15}, hole_top);
  for (int k = 0; k < 4; k++) {
    const int a = k, b = (k + 1) % 4;
    set_facet(in.facetlist[2 + k], {a, b, b + 4, a + 4}, {}, nullptr);
    set_facet(in.facetlist[6 + k], {8 + a, 8 + b, 12 + b, 12 + a}, {}, nullptr);
  }
  // p: a piecewise linear complex; q: radius-edge ratio at most 1.4; a: volume at most
  // 0.05; Q: quiet.
  tetgenbehavior options;
  char switches[] = "pq1.4a0.05Q";
  if (!options.parse_commandline(switches)) throw std::runtime_error("TetGen switches");
  tetrahedralize(&options, &in, &out);
  std::printf("TetGen: %d points, %d tets\n", out.numberofpoints, out.numberoftetrahedra);
  verify(out.numberofcorners == 4 && out.firstnumber == 0, "linear tets numbered from 0");
  std::vector<uint32_t> tets(out.tetrahedronlist, out.tetrahedronlist + 4 * out.numberoftetrahedra);
  mtcut_mesh *raw = nullptr;
  // TetGen lists tets with the other orientation; mtcut re-orients them on the way in.
  check(mtcut_mesh_from_arrays(out.pointlist, static_cast<size_t>(out.numberofpoints), tets.data(),
                               static_cast<size_t>(out.numberoftetrahedra), &raw),
        "mesh from TetGen's arrays");
  return Mesh(raw);
}

// The build's progress, printed every tenth of the way.
struct Progress {
  double next = 0.0;
  int calls = 0;
};

int report(void *user, double fraction) {
  Progress *p = static_cast<Progress *>(user);
  p->calls++;
  if (fraction >= p->next) {
    std::printf("  build %3.0f%%\n", 100.0 * fraction);
    p->next = std::floor(fraction * 10.0 + 1.0) / 10.0;
  }
  return 0;  // nonzero would cancel the build
}

}  // namespace

int main(int argc, char **argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  try {
    Mesh input = tetrahedralize_box_with_hole();
    const double v0 = volume(input.get());
    verify(std::fabs(v0 - 30.0) < 1e-9, "the box with a hole has volume 30");
    verify_valid(input.get(), "TetGen's mesh");

    // The Multi-Tessellation, with a progress callback.
    mtcut_build_options options;
    options.struct_size = sizeof options;
    check(mtcut_build_options_default(&options), "build options");
    Progress progress;
    options.progress_or_null = report;
    options.user = &progress;
    mtcut_mt *raw_mt = nullptr;
    check(mtcut_mt_build(input.get(), &options, &raw_mt), "build");
    Mt built(raw_mt);
    const mtcut_mt_stats st = statistics(built.get());
    std::printf("MT: %zu fragments, DAG depth %zu, %zu tets over all levels (input %zu, coarsest "
                "%zu), errors %.3g..%.3g, %zu bytes; %d progress calls\n",
                st.fragments, st.dag_depth, st.tets, st.input_tets, st.coarsest_tets,
                st.min_error, st.max_error, st.heap_bytes, progress.calls);
    verify(progress.calls > 0 && st.coarsest_tets < st.input_tets, "the model simplifies");

    // Saved and loaded: the same model.
    const std::string saved = dir + "/box-with-hole.mt";
    check(mtcut_mt_save(built.get(), saved.c_str()), "save");
    check(mtcut_mt_load(saved.c_str(), &raw_mt), "load");
    Mt mt(raw_mt);
    const mtcut_mt_stats back = statistics(mt.get());
    verify(back.fragments == st.fragments && back.tets == st.tets && back.max_error == st.max_error,
           "the loaded model is the saved one");

    // Two thresholds: 0 (the input) and a middle error.
    mtcut_mesh *raw = nullptr;
    check(mtcut_mt_extract_threshold(mt.get(), 0.0, &raw), "finest");
    Mesh finest(raw);
    verify(mtcut_mesh_tet_count(finest.get()) == st.input_tets, "threshold 0 gives the input");
    const double middle = std::sqrt(st.min_error * st.max_error);
    check(mtcut_mt_extract_threshold(mt.get(), middle, &raw), "coarse");
    Mesh coarse(raw);
    verify_valid(coarse.get(), "coarse extraction");
    const size_t nc = mtcut_mesh_tet_count(coarse.get());
    std::printf("threshold %.3g: %zu tets (volume %.6g); threshold 0: %zu tets\n", middle, nc,
                volume(coarse.get()), mtcut_mesh_tet_count(finest.get()));
    verify(nc < st.input_tets && std::fabs(volume(coarse.get()) - 30.0) < 0.3,
           "coarser, and the shape kept (corners and edges are features)");
    mtcut_example_write_vtu(coarse.get(), dir.c_str(), "tetgen-coarse.vtu");

    // A frontier: full resolution around one corner of the hole, moved to another.
    mtcut_extract_options focus;
    focus.struct_size = sizeof focus;
    check(mtcut_extract_options_default(&focus), "extract options");
    focus.threshold = INFINITY;
    focus.focus = MTCUT_FOCUS_SPHERE;
    focus.focus_threshold = 0.0;
    focus.focus_radius = 0.5;
    focus.focus_center[0] = focus.focus_center[1] = 1.5;
    focus.focus_center[2] = 2.0;
    mtcut_frontier *raw_frontier = nullptr;
    check(mtcut_frontier_new(mt.get(), &focus, &raw_frontier), "frontier");
    Frontier frontier(raw_frontier);
    focus.focus_center[0] = 2.5;
    mtcut_frontier_update_stats moved;
    moved.struct_size = sizeof moved;
    check(mtcut_frontier_update(frontier.get(), &focus, &moved), "frontier update");
    check(mtcut_frontier_mesh(frontier.get(), &raw), "frontier mesh");
    Mesh focused(raw);
    mtcut_extract_stats fresh_stats;
    fresh_stats.struct_size = sizeof fresh_stats;
    check(mtcut_mt_extract(mt.get(), &focus, &fresh_stats, &raw), "fresh extraction");
    Mesh fresh(raw);
    std::printf("focus moved: %zu fragments examined, %zu refined, %zu coarsened, %zu tets "
                "(a fresh extraction: %zu)\n",
                moved.candidates, moved.refined, moved.coarsened, moved.tets, fresh_stats.tets);
    verify(moved.tets == fresh_stats.tets && mtcut_mesh_tet_count(focused.get()) == moved.tets,
           "the frontier's mesh is the fresh extraction's");
    verify_valid(focused.get(), "frontier mesh");
    mtcut_example_write_vtu(focused.get(), dir.c_str(), "tetgen-focus.vtu");

    // A region of interest (paper section 7): the half x < 2 as a model of its own, the
    // rest omitted; its finest mesh is the input's half (volume 16, less the hole's 1).
    const double roi_min[3] = {-1, -1, -1}, roi_max[3] = {2, 5, 3};
    mtcut_mt *raw_roi = nullptr;
    check(mtcut_mt_roi_box(mt.get(), roi_min, roi_max, &raw_roi), "region of interest");
    Mt roi(raw_roi);
    bool roi_valid = false;
    check(mtcut_mt_validate(roi.get(), &roi_valid, nullptr, 0, nullptr), "sub-model validation");
    verify(roi_valid && statistics(roi.get()).components == 1, "the sub-model is one valid model");
    check(mtcut_mt_extract_threshold(roi.get(), 0.0, &raw), "the sub-model's finest mesh");
    Mesh roi_finest(raw);
    verify_valid(roi_finest.get(), "the sub-model's finest mesh");
    std::printf("region x < 2: %zu tets over all levels, finest mesh %zu tets, volume %.12g\n",
                statistics(roi.get()).tets, mtcut_mesh_tet_count(roi_finest.get()),
                volume(roi_finest.get()));
    verify(std::fabs(volume(roi_finest.get()) - 15.0) < 1e-9, "the finest mesh is the half");
    verify(statistics(mt.get()).tets == back.tets, "the model given is unchanged");

    // The finest extraction cut right through by the plane x = 0.9 (a large square).
    const double square[12] = {0.9, -1, -1, 0.9, 5, -1, 0.9, 5, 3, 0.9, -1, 3};
    mtcut_cut_stats cut;
    std::memset(&cut, 0, sizeof cut);
    cut.struct_size = sizeof cut;
    check(mtcut_mesh_cut(finest.get(), square, 4, &cut), "cut");
    std::printf("cut: %zu tets cut, %zu created, %zu vertices added, %zu components, %.3f ms\n",
                cut.tets_cut, cut.tets_created, cut.vertices_added, cut.components,
                1e3 * cut.seconds_cut);
    verify_valid(finest.get(), "cut mesh");
    verify(cut.components == 2 && components(finest.get()) == 2, "two pieces");
    verify(std::fabs(volume(finest.get()) - 30.0) < 1e-9, "the volume is kept");
    mtcut_example_write_vtu(finest.get(), dir.c_str(), "tetgen-cut.vtu");

    // The model itself cut by the same plane: every level at once (paper section 3). The
    // body falls into two independent models; each level keeps its volume.
    const double coarse_volume = volume(coarse.get());
    mtcut_cut_stats mt_cut;
    std::memset(&mt_cut, 0, sizeof mt_cut);
    mt_cut.struct_size = sizeof mt_cut;
    check(mtcut_mt_cut(mt.get(), square, 4, &mt_cut), "model cut");
    const mtcut_mt_stats after = statistics(mt.get());
    std::printf("model cut: %zu tets of all levels cut, %zu created, %zu components, %.3f ms\n",
                mt_cut.tets_cut, mt_cut.tets_created, after.components, 1e3 * mt_cut.seconds_cut);
    verify(after.components == 2, "the model cut through is two models");
    bool model_valid = false;
    char report[64];
    check(mtcut_mt_validate(mt.get(), &model_valid, report, sizeof report, nullptr),
          "model validation");
    verify(model_valid && std::strcmp(report, "valid MT") == 0, "the cut model is valid");
    check(mtcut_mt_extract_threshold(mt.get(), middle, &raw), "coarse level of the cut model");
    Mesh coarse_cut(raw);
    verify_valid(coarse_cut.get(), "coarse level of the cut model");
    verify(components(coarse_cut.get()) == 2, "the coarse level is in two pieces");
    verify(std::fabs(volume(coarse_cut.get()) - coarse_volume) < 1e-12 * coarse_volume,
           "the coarse level keeps its volume");
    mtcut_example_write_vtu(coarse_cut.get(), dir.c_str(), "tetgen-mt-cut-coarse.vtu");
    mtcut_mt *raw_part = nullptr;
    check(mtcut_mt_component(mt.get(), 1, &raw_part), "component 1");
    Mt part(raw_part);
    verify(statistics(part.get()).components == 1, "a component is one model");
  } catch (const std::exception &e) {
    std::fprintf(stderr, "tetgen_mt: %s\n", e.what());
    return 1;
  }
  return 0;
}
