/* cut_basics: cutting a mesh through the mtcut C API, in plain C99.
 *
 * Builds a 4 x 4 x 2 block of cubes (each split into six tets) from arrays, with a
 * per-vertex "temperature" and a per-tet "material", cuts it with a polygon reaching only
 * part way in (a notch), prints the statistics, then cuts it right through with a scalpel
 * sweep and takes the two components apart. Checks each result (valid, volume kept,
 * counts consistent with the statistics) and writes cut-notch.vtu, cut-through.vtu and
 * cut-part0.vtu with a JSON sidecar each (FILE.vtu.json: the counts, volume and array
 * names mtcut reports, which check_vtu.py and scripts/pvbatch-check.py compare with what
 * VTK and ParaView read). Exits 1 on the first surprise, so ctest can run it.
 *
 * Usage: cut_basics OUTPUT_DIR
 */
#include <mtcut.h>

#include "sidecar.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CHECK(call)                                                                     \
  do {                                                                                  \
    mtcut_status status_ = (call);                                                      \
    if (status_ != MTCUT_STATUS_OK) {                                                   \
      fprintf(stderr, "%s:%d: %s: %s\n  %s\n", __FILE__, __LINE__, #call,               \
              mtcut_status_message(status_), mtcut_last_error_message());               \
      exit(1);                                                                          \
    }                                                                                   \
  } while (0)

#define VERIFY(cond)                                                                     \
  do {                                                                                   \
    if (!(cond)) {                                                                       \
      fprintf(stderr, "%s:%d: unexpected result: %s\n", __FILE__, __LINE__, #cond);      \
      exit(1);                                                                           \
    }                                                                                    \
  } while (0)

enum { NX = 4, NY = 4, NZ = 2 };
#define VID(i, j, k) ((uint32_t)((i) + (NX + 1) * ((j) + (NY + 1) * (k))))

static int close_to(double a, double b) { return fabs(a - b) <= 1e-9 * (1.0 + fabs(b)); }

/* The block: (NX+1)(NY+1)(NZ+1) grid vertices, six tets per cube (Kuhn's subdivision
 * around the cube's diagonal, the same in every cube so that faces match). */
static mtcut_mesh *block(void) {
  static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  static const int kuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                 {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  const size_t nv = (NX + 1) * (NY + 1) * (NZ + 1), nt = 6 * NX * NY * NZ;
  double *xyz = malloc(3 * nv * sizeof *xyz), *temperature = malloc(nv * sizeof(double));
  double *material = malloc(nt * sizeof(double));
  uint32_t *tets = malloc(4 * nt * sizeof *tets);
  mtcut_mesh *mesh = NULL;
  size_t t = 0;
  int i, j, k, c, q;

  VERIFY(xyz && temperature && material && tets);
  for (k = 0; k <= NZ; k++)
    for (j = 0; j <= NY; j++)
      for (i = 0; i <= NX; i++) {
        uint32_t v = VID(i, j, k);
        xyz[3 * v] = i;
        xyz[3 * v + 1] = j;
        xyz[3 * v + 2] = k;
        temperature[v] = 20.0 + 10.0 * k;
      }
  for (k = 0; k < NZ; k++)
    for (j = 0; j < NY; j++)
      for (i = 0; i < NX; i++)
        for (c = 0; c < 6; c++, t++) {
          for (q = 0; q < 4; q++) {
            const int *d = corner[kuhn[c][q]];
            tets[4 * t + q] = VID(i + d[0], j + d[1], k + d[2]);
          }
          material[t] = (double)(i < NX / 2);
        }
  CHECK(mtcut_mesh_from_arrays(xyz, nv, tets, nt, &mesh));
  CHECK(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "temperature", temperature, nv, 1));
  CHECK(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_TET, "material", material, nt, 1));
  free(xyz);
  free(temperature);
  free(material);
  free(tets);
  return mesh;
}

static void print_stats(const char *what, const mtcut_cut_stats *s) {
  printf("%s: %lu tets tested, %lu cut, %lu created; %lu vertices added (%lu cut points, "
         "%lu crack tips, %lu copies; %lu snapped); now %lu tets, %lu vertices, %lu "
         "component(s); %.3f ms (+%.3f ms hierarchy)\n",
         what, (unsigned long)s->tets_tested, (unsigned long)s->tets_cut,
         (unsigned long)s->tets_created, (unsigned long)s->vertices_added,
         (unsigned long)s->cut_points, (unsigned long)s->face_points,
         (unsigned long)s->vertex_copies, (unsigned long)s->vertices_snapped,
         (unsigned long)s->tets_after, (unsigned long)s->vertices_after,
         (unsigned long)s->components, 1e3 * s->seconds_cut, 1e3 * s->seconds_build);
}

/* What every cut must keep: a valid mesh of the same volume, counts as reported. */
static void check_after(const mtcut_mesh *mesh, const mtcut_cut_stats *s, double volume,
                        size_t tets_before) {
  bool valid = false;
  char message[256];
  double v = 0.0;
  size_t components = 0;
  CHECK(mtcut_mesh_validate(mesh, &valid, message, sizeof message, NULL));
  CHECK(mtcut_mesh_volume(mesh, &v));
  CHECK(mtcut_mesh_component_count(mesh, &components));
  if (!valid) fprintf(stderr, "%s\n", message);
  VERIFY(valid);
  VERIFY(close_to(v, volume));
  VERIFY(s->tets_after == mtcut_mesh_tet_count(mesh));
  VERIFY(s->vertices_after == mtcut_mesh_vertex_count(mesh));
  VERIFY(s->tets_after == tets_before - s->tets_cut + s->tets_created);
  VERIFY(s->components == components);
}

int main(int argc, char **argv) {
  mtcut_mesh *mesh, *part = NULL;
  mtcut_cut_options options;
  mtcut_cut_stats stats;
  double volume = 0.0, part_volume[2] = {0, 0}, temperature[4096];
  size_t tets, components = 0, k, n;
  /* A rectangle in the plane x = 2.3, reaching from above down to z = 1.2 only: a notch. */
  const double notch[12] = {2.3, -1, 3, 2.3, 5, 3, 2.3, 5, 1.2, 2.3, -1, 1.2};
  /* A blade along y at height 3, swept down to -1 while moving from x = 1.3 to x = 1.7: a
   * slanted plane through the whole block. */
  const double blade_start[6] = {1.3, -1, 3, 1.3, 5, 3};
  const double blade_end[6] = {1.7, -1, -1, 1.7, 5, -1};

  if (argc != 2) {
    fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  mesh = block();
  CHECK(mtcut_mesh_volume(mesh, &volume));
  VERIFY(close_to(volume, NX * NY * NZ));
  printf("block: %lu vertices, %lu tets, volume %g\n", (unsigned long)mtcut_mesh_vertex_count(mesh),
         (unsigned long)mtcut_mesh_tet_count(mesh), volume);

  /* A cut with the default options. */
  memset(&stats, 0, sizeof stats);
  stats.struct_size = sizeof stats; /* versioned struct: say which version this program knows */
  tets = mtcut_mesh_tet_count(mesh);
  CHECK(mtcut_mesh_cut(mesh, notch, 4, &stats));
  print_stats("notch", &stats);
  check_after(mesh, &stats, volume, tets);
  VERIFY(stats.tets_cut > 0 && stats.components == 1); /* a notch does not separate */
  mtcut_example_write_vtu(mesh, argv[1], "cut-notch.vtu");

  /* How far the blade moves in that sweep, in the mesh's median edges: a host moving a
     blade in steps much shorter than one defers them (mtcut_blade_advance). */
  {
    double edge = 0.0, advance = 0.0;
    CHECK(mtcut_mesh_median_edge_length(mesh, &edge));
    CHECK(mtcut_blade_advance(blade_start, blade_end, &advance));
    VERIFY(edge > 0.0 && advance > 0.0);
    printf("sweep: the blade moves %.2f median edges\n", advance / edge);
  }

  /* A scalpel sweep with explicit options: defaults first, then what differs. */
  options.struct_size = sizeof options;
  CHECK(mtcut_cut_options_default(&options));
  options.snap = 0.1;
  tets = mtcut_mesh_tet_count(mesh);
  CHECK(mtcut_mesh_scalpel_sweep(mesh, blade_start, blade_end, &options, &stats));
  print_stats("sweep", &stats);
  check_after(mesh, &stats, volume, tets);
  VERIFY(stats.components == 2);
  mtcut_example_write_vtu(mesh, argv[1], "cut-through.vtu");

  /* The two pieces, each a mesh of its own with its attribute rows. */
  CHECK(mtcut_mesh_component_count(mesh, &components));
  for (k = 0; k < components; k++) {
    CHECK(mtcut_mesh_extract_component(mesh, k, &part));
    CHECK(mtcut_mesh_volume(part, &part_volume[k]));
    n = mtcut_mesh_vertex_count(part);
    VERIFY(n <= sizeof temperature / sizeof temperature[0]);
    /* Cut points get interpolated rows: every temperature stays within 20..40. */
    CHECK(mtcut_mesh_copy_attribute(part, MTCUT_LOCATION_VERTEX, "temperature", temperature, n));
    while (n-- > 0) VERIFY(temperature[n] >= 20.0 && temperature[n] <= 40.0);
    printf("component %lu: %lu tets, volume %.6g\n", (unsigned long)k,
           (unsigned long)mtcut_mesh_tet_count(part), part_volume[k]);
    if (k == 0) mtcut_example_write_vtu(part, argv[1], "cut-part0.vtu");
    mtcut_mesh_free(part);
  }
  VERIFY(close_to(part_volume[0] + part_volume[1], volume));
  mtcut_mesh_free(mesh);
  return 0;
}
