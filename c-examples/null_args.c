/* null_args: every function of mtcut.h called with NULL and invalid arguments.
 *
 * Each call must return the documented status, leave a non-empty message in
 * mtcut_last_error_message(), and leave every output untouched. Nothing may crash.
 * tests/ffi_header.rs checks that every function the header declares is called here:
 * when a function is added to the API, add its checks here.
 *
 * Usage: null_args SCRATCH_DIR   (files are written there)
 */
#include <mtcut.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;

/* Checks a call's status and, for a failure, that a message was left. */
static void expect(mtcut_status got, mtcut_status want, const char *call, int line) {
  const char *message = mtcut_last_error_message();
  if (got != want) {
    fprintf(stderr, "null_args.c:%d: %s returned %u (%s), expected %u (%s); message: %s\n", line,
            call, (unsigned)got, mtcut_status_message(got), (unsigned)want,
            mtcut_status_message(want), message);
    failures++;
  } else if (want != MTCUT_STATUS_OK && (message == NULL || message[0] == '\0')) {
    fprintf(stderr, "null_args.c:%d: %s left no error message\n", line, call);
    failures++;
  } else if (want == MTCUT_STATUS_OK && message[0] != '\0') {
    fprintf(stderr, "null_args.c:%d: %s succeeded but left a message: %s\n", line, call, message);
    failures++;
  }
}
#define EXPECT(call, want) expect((call), (want), #call, __LINE__)

/* Checks that a count function refused its arguments: 0 and a message. */
static void expect_zero(size_t got, const char *call, int line) {
  const char *message = mtcut_last_error_message();
  if (got != 0 || message[0] == '\0') {
    fprintf(stderr, "null_args.c:%d: %s returned %lu with message \"%s\"\n", line, call,
            (unsigned long)got, message);
    failures++;
  }
}
#define EXPECT_ZERO(call) expect_zero((call), #call, __LINE__)

/* Checks a condition on outputs (that they were left untouched). */
#define UNTOUCHED(cond)                                                  \
  do {                                                                   \
    if (!(cond)) {                                                       \
      fprintf(stderr, "null_args.c:%d: modified: %s\n", __LINE__, #cond); \
      failures++;                                                        \
    }                                                                    \
  } while (0)

/* A unit cube split into six tets around its diagonal 0-7. */
static const double cube_xyz[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,
                                    0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
static const uint32_t cube_tets[24] = {0, 1, 3, 7, 0, 1, 5, 7, 0, 2, 3, 7,
                                       0, 2, 6, 7, 0, 4, 5, 7, 0, 4, 6, 7};

static void path_in(char *out, size_t size, const char *dir, const char *name) {
  snprintf(out, size, "%s/%s", dir, name);
}

static void check_status_and_version(void) {
  mtcut_status s;
  for (s = 0; s <= MTCUT_STATUS_INTERNAL_PANIC + 1; s++) {
    const char *text = mtcut_status_message(s);
    if (text == NULL || text[0] == '\0') {
      fprintf(stderr, "mtcut_status_message(%u) is empty\n", (unsigned)s);
      failures++;
    }
  }
  if (strcmp(mtcut_status_message(0xFFFFFFFFu), "unknown status code") != 0) failures++;
  if (mtcut_last_error_message() == NULL) failures++;
  if (strcmp(mtcut_version(), MTCUT_VERSION_STRING) != 0 ||
      mtcut_version_major() != MTCUT_VERSION_MAJOR ||
      mtcut_version_minor() != MTCUT_VERSION_MINOR ||
      mtcut_version_patch() != MTCUT_VERSION_PATCH) {
    fprintf(stderr, "library %s, header %s\n", mtcut_version(), MTCUT_VERSION_STRING);
    failures++;
  }
}

static void check_from_arrays(void) {
  mtcut_mesh *sentinel = (mtcut_mesh *)&failures; /* any non-NULL value; never dereferenced */
  mtcut_mesh *out = sentinel;
  uint32_t bad_tets[24];
  double bad_xyz[24];

  EXPECT(mtcut_mesh_from_arrays(NULL, 8, cube_tets, 6, &out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_from_arrays(cube_xyz, 8, NULL, 6, &out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_from_arrays(cube_xyz, 8, cube_tets, 6, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_from_arrays(cube_xyz, SIZE_MAX, cube_tets, 6, &out),
         MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_from_arrays(cube_xyz, 8, cube_tets, 0, &out), MTCUT_STATUS_INVALID_MESH);
  memcpy(bad_tets, cube_tets, sizeof bad_tets);
  bad_tets[3] = 8; /* out of range */
  EXPECT(mtcut_mesh_from_arrays(cube_xyz, 8, bad_tets, 6, &out), MTCUT_STATUS_INVALID_MESH);
  bad_tets[3] = 0; /* repeated vertex */
  EXPECT(mtcut_mesh_from_arrays(cube_xyz, 8, bad_tets, 6, &out), MTCUT_STATUS_INVALID_MESH);
  memcpy(bad_xyz, cube_xyz, sizeof bad_xyz);
  bad_xyz[4] = NAN;
  EXPECT(mtcut_mesh_from_arrays(bad_xyz, 8, cube_tets, 6, &out), MTCUT_STATUS_INVALID_MESH);
  UNTOUCHED(out == sentinel);
}

static void check_files(const mtcut_mesh *mesh, const char *dir) {
  mtcut_mesh *sentinel = (mtcut_mesh *)&failures;
  mtcut_mesh *out = sentinel;
  char path[4096];
  FILE *f;

  EXPECT(mtcut_mesh_read(NULL, &out), MTCUT_STATUS_NULL_ARGUMENT);
  path_in(path, sizeof path, dir, "cube.node");
  EXPECT(mtcut_mesh_read(path, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  path_in(path, sizeof path, dir, "does-not-exist.node");
  EXPECT(mtcut_mesh_read(path, &out), MTCUT_STATUS_IO_ERROR);
  path_in(path, sizeof path, dir, "cube.unknown");
  EXPECT(mtcut_mesh_read(path, &out), MTCUT_STATUS_UNSUPPORTED_FORMAT);
  path_in(path, sizeof path, dir, "bad.node");
  f = fopen(path, "w");
  if (f == NULL) {
    perror(path);
    failures++;
    return;
  }
  fputs("4 3 0 0\n0 0 0 0\n1 1 0 not-a-number\n", f);
  fclose(f);
  path_in(path, sizeof path, dir, "bad.ele");
  f = fopen(path, "w");
  if (f != NULL) {
    fputs("1 4 0\n0 0 1 2 3\n", f);
    fclose(f);
  }
  path_in(path, sizeof path, dir, "bad.node");
  EXPECT(mtcut_mesh_read(path, &out), MTCUT_STATUS_PARSE_ERROR);
  UNTOUCHED(out == sentinel);

  path_in(path, sizeof path, dir, "cube.node");
  EXPECT(mtcut_mesh_write(NULL, path), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_write(mesh, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  path_in(path, sizeof path, dir, "cube.unknown");
  EXPECT(mtcut_mesh_write(mesh, path), MTCUT_STATUS_UNSUPPORTED_FORMAT);
  path_in(path, sizeof path, dir, "no-such-dir/cube.node");
  EXPECT(mtcut_mesh_write(mesh, path), MTCUT_STATUS_IO_ERROR);

  path_in(path, sizeof path, dir, "cube.vtu");
  EXPECT(mtcut_mesh_write_vtu(NULL, path), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_write_vtu(mesh, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  path_in(path, sizeof path, dir, "cube.txt");
  EXPECT(mtcut_mesh_write_vtu(mesh, path), MTCUT_STATUS_INVALID_ARGUMENT);
}

static void check_arrays_out(mtcut_mesh *mesh) {
  double xyz[24];
  uint32_t tets[24];
  mtcut_mesh *sentinel = (mtcut_mesh *)&failures;
  mtcut_mesh *out = sentinel;
  double moved[24];
  int i;

  EXPECT_ZERO(mtcut_mesh_vertex_count(NULL));
  EXPECT_ZERO(mtcut_mesh_tet_count(NULL));

  for (i = 0; i < 24; i++) xyz[i] = -1.0;
  EXPECT(mtcut_mesh_copy_vertices(NULL, xyz, 8), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_copy_vertices(mesh, NULL, 8), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_copy_vertices(mesh, xyz, 7), MTCUT_STATUS_BUFFER_TOO_SMALL);
  EXPECT(mtcut_mesh_copy_vertices(mesh, xyz, 0), MTCUT_STATUS_BUFFER_TOO_SMALL);
  for (i = 0; i < 24; i++) UNTOUCHED(xyz[i] == -1.0);

  for (i = 0; i < 24; i++) tets[i] = 99;
  EXPECT(mtcut_mesh_copy_tets(NULL, tets, 6), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_copy_tets(mesh, NULL, 6), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_copy_tets(mesh, tets, 5), MTCUT_STATUS_BUFFER_TOO_SMALL);
  for (i = 0; i < 24; i++) UNTOUCHED(tets[i] == 99);

  memcpy(moved, cube_xyz, sizeof moved);
  moved[0] = 0.5;
  EXPECT(mtcut_mesh_set_vertices(NULL, moved, 8), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_set_vertices(mesh, NULL, 8), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_set_vertices(mesh, moved, 7), MTCUT_STATUS_INVALID_ARGUMENT);
  moved[23] = INFINITY;
  EXPECT(mtcut_mesh_set_vertices(mesh, moved, 8), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_copy_vertices(mesh, xyz, 8), MTCUT_STATUS_OK);
  UNTOUCHED(memcmp(xyz, cube_xyz, sizeof xyz) == 0);

  EXPECT(mtcut_mesh_clone(NULL, &out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_clone(mesh, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(out == sentinel);
  mtcut_mesh_free(NULL); /* allowed: nothing happens */
}

static void check_measures(const mtcut_mesh *mesh) {
  bool valid = false;
  char message[16] = "untouched";
  size_t length = 12345, count = 12345, faces = 12345;
  double volume = -1.0, area = -1.0, lo[3] = {-1, -1, -1}, hi[3] = {-1, -1, -1};
  mtcut_quality q;
  mtcut_mesh *sentinel = (mtcut_mesh *)&failures;
  mtcut_mesh *out = sentinel;

  EXPECT(mtcut_mesh_validate(NULL, &valid, message, sizeof message, &length),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_validate(mesh, NULL, message, sizeof message, &length),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_validate(mesh, &valid, NULL, sizeof message, &length),
         MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(!valid && strcmp(message, "untouched") == 0 && length == 12345);

  EXPECT(mtcut_mesh_volume(NULL, &volume), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_volume(mesh, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_median_edge_length(NULL, &volume), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_median_edge_length(mesh, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(volume == -1.0);

  EXPECT(mtcut_mesh_bounding_box(NULL, lo, hi), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_bounding_box(mesh, NULL, hi), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_bounding_box(mesh, lo, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(lo[0] == -1 && hi[0] == -1);

  EXPECT(mtcut_mesh_boundary(NULL, &faces, &area), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_boundary(mesh, NULL, &area), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_boundary(mesh, &faces, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(faces == 12345 && area == -1.0);

  memset(&q, 0, sizeof q);
  q.struct_size = sizeof q;
  EXPECT(mtcut_mesh_quality(NULL, &q), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_quality(mesh, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  q.struct_size = 0;
  EXPECT(mtcut_mesh_quality(mesh, &q), MTCUT_STATUS_INVALID_ARGUMENT);
  q.struct_size = sizeof q + 64; /* a newer header than this library */
  EXPECT(mtcut_mesh_quality(mesh, &q), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(q.tets == 0);

  EXPECT(mtcut_mesh_component_count(NULL, &count), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_component_count(mesh, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(count == 12345);
  EXPECT(mtcut_mesh_extract_component(NULL, 0, &out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_extract_component(mesh, 0, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_extract_component(mesh, 1, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_extract_component(mesh, SIZE_MAX, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(out == sentinel);
}

static void check_attributes(mtcut_mesh *mesh) {
  double values[24] = {0};
  double out[24];
  size_t count = 12345, components = 12345, length = 12345;
  char name[4] = "abc";
  int i;

  EXPECT(mtcut_mesh_set_attribute(NULL, MTCUT_LOCATION_VERTEX, "t", values, 8, 1),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, NULL, values, 8, 1),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "t", NULL, 8, 1),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, 2, "t", values, 8, 1), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, 0xFFFFFFFFu, "t", values, 8, 1),
         MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_TET, "t", values, 8, 1),
         MTCUT_STATUS_INVALID_ARGUMENT); /* 6 tets, not 8 */
  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "t", values, 8, 0),
         MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_TET, "t", values, 6,
                                  MTCUT_MAX_COMPONENTS + 1),
         MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "", values, 8, 1),
         MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "\xff\xfe", values, 8, 1),
         MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "t", values, SIZE_MAX, 2),
         MTCUT_STATUS_INVALID_ARGUMENT);

  EXPECT(mtcut_mesh_attribute_count(NULL, MTCUT_LOCATION_VERTEX, &count),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_count(mesh, MTCUT_LOCATION_VERTEX, NULL),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_count(mesh, 7, &count), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(count == 12345);
  EXPECT(mtcut_mesh_attribute_count(mesh, MTCUT_LOCATION_VERTEX, &count), MTCUT_STATUS_OK);
  UNTOUCHED(count == 0); /* every refusal above left the mesh without columns */

  EXPECT(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "temp", values, 8, 1),
         MTCUT_STATUS_OK);
  EXPECT(mtcut_mesh_attribute_name(NULL, MTCUT_LOCATION_VERTEX, 0, name, sizeof name, &length),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_name(mesh, MTCUT_LOCATION_VERTEX, 0, NULL, 8, &length),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_name(mesh, 3, 0, name, sizeof name, &length),
         MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_name(mesh, MTCUT_LOCATION_VERTEX, 1, name, sizeof name, &length),
         MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(length == 12345);
  /* "temp" needs 5 bytes: the length is reported, the buffer left alone. */
  EXPECT(mtcut_mesh_attribute_name(mesh, MTCUT_LOCATION_VERTEX, 0, name, sizeof name, &length),
         MTCUT_STATUS_BUFFER_TOO_SMALL);
  UNTOUCHED(strcmp(name, "abc") == 0);
  if (length != 4) failures++;

  EXPECT(mtcut_mesh_attribute_components(NULL, MTCUT_LOCATION_VERTEX, "temp", &components),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_components(mesh, MTCUT_LOCATION_VERTEX, NULL, &components),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_components(mesh, MTCUT_LOCATION_VERTEX, "temp", NULL),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_components(mesh, MTCUT_LOCATION_TET, "temp", &components),
         MTCUT_STATUS_NOT_FOUND);
  EXPECT(mtcut_mesh_attribute_components(mesh, 9, "temp", &components),
         MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(components == 12345);

  for (i = 0; i < 24; i++) out[i] = -7.0;
  EXPECT(mtcut_mesh_copy_attribute(NULL, MTCUT_LOCATION_VERTEX, "temp", out, 24),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_copy_attribute(mesh, MTCUT_LOCATION_VERTEX, NULL, out, 24),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_copy_attribute(mesh, MTCUT_LOCATION_VERTEX, "temp", NULL, 24),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_copy_attribute(mesh, MTCUT_LOCATION_VERTEX, "nope", out, 24),
         MTCUT_STATUS_NOT_FOUND);
  EXPECT(mtcut_mesh_copy_attribute(mesh, MTCUT_LOCATION_VERTEX, "temp", out, 7),
         MTCUT_STATUS_BUFFER_TOO_SMALL);
  EXPECT(mtcut_mesh_copy_attribute(mesh, 2, "temp", out, 24), MTCUT_STATUS_INVALID_ARGUMENT);
  for (i = 0; i < 24; i++) UNTOUCHED(out[i] == -7.0);

  EXPECT(mtcut_mesh_remove_attribute(NULL, MTCUT_LOCATION_VERTEX, "temp"),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_remove_attribute(mesh, MTCUT_LOCATION_VERTEX, NULL),
         MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_remove_attribute(mesh, MTCUT_LOCATION_TET, "temp"), MTCUT_STATUS_NOT_FOUND);
  EXPECT(mtcut_mesh_remove_attribute(mesh, 5, "temp"), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_attribute_count(mesh, MTCUT_LOCATION_VERTEX, &count), MTCUT_STATUS_OK);
  UNTOUCHED(count == 1);
}

/* A triangle across the cube at z = 0.5, larger than the cube. */
static const double plane_xyz[9] = {-1, -1, 0.5, 5, -1, 0.5, -1, 5, 0.5};

static void check_cut(mtcut_mesh *mesh) {
  mtcut_cut_options o;
  mtcut_cut_stats st;
  double bad[9];
  const double start[6] = {-1, 0.5, 0.5, 2, 0.5, 0.5};
  const double end_same[6] = {-1, 0.5, 0.5, 2, 0.5, 0.5};
  const size_t tets = mtcut_mesh_tet_count(mesh);

  memset(&o, 0, sizeof o);
  EXPECT(mtcut_cut_options_default(NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_cut_options_default(&o), MTCUT_STATUS_INVALID_ARGUMENT); /* struct_size 0 */
  UNTOUCHED(o.snap == 0.0);
  o.struct_size = sizeof o;
  EXPECT(mtcut_cut_options_default(&o), MTCUT_STATUS_OK);
  UNTOUCHED(o.struct_size == sizeof o && o.scheme == MTCUT_CUT_SCHEME_LUT && o.snap > 0.0);
  {
    mtcut_cut_options sc;
    memset(&sc, 0, sizeof sc);
    EXPECT(mtcut_cut_options_scalpel(NULL), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_cut_options_scalpel(&sc), MTCUT_STATUS_INVALID_ARGUMENT); /* struct_size 0 */
    UNTOUCHED(sc.snap == 0.0 && sc.continue_cracks == 0);
    sc.struct_size = sizeof sc;
    EXPECT(mtcut_cut_options_scalpel(&sc), MTCUT_STATUS_OK);
    UNTOUCHED(sc.continue_cracks == 1 && sc.snap < o.snap && sc.face_point_margin < o.face_point_margin);
  }

  memset(&st, 0, sizeof st);
  st.struct_size = sizeof st;
  EXPECT(mtcut_mesh_cut(NULL, plane_xyz, 3, &st), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_cut(mesh, NULL, 3, &st), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_cut(mesh, plane_xyz, 2, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mesh_cut(mesh, plane_xyz, SIZE_MAX, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  memcpy(bad, plane_xyz, sizeof bad);
  bad[4] = NAN;
  EXPECT(mtcut_mesh_cut(mesh, bad, 3, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  memcpy(bad, plane_xyz, sizeof bad);
  bad[3] = bad[0]; bad[4] = bad[1]; bad[5] = bad[2]; /* repeated corner */
  EXPECT(mtcut_mesh_cut(mesh, bad, 3, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  st.struct_size = 1;
  EXPECT(mtcut_mesh_cut(mesh, plane_xyz, 3, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(st.tets_cut == 0);

  st.struct_size = sizeof st;
  EXPECT(mtcut_mesh_cut_with_options(NULL, plane_xyz, 3, &o, &st), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_cut_with_options(mesh, NULL, 3, &o, &st), MTCUT_STATUS_NULL_ARGUMENT);
  o.scheme = 2;
  EXPECT(mtcut_mesh_cut_with_options(mesh, plane_xyz, 3, &o, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  o.scheme = 0xFFFFFFFFu;
  EXPECT(mtcut_mesh_cut_with_options(mesh, plane_xyz, 3, &o, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  o.scheme = MTCUT_CUT_SCHEME_LUT;
  o.snap = 0.3;
  EXPECT(mtcut_mesh_cut_with_options(mesh, plane_xyz, 3, &o, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  o.snap = NAN;
  EXPECT(mtcut_mesh_cut_with_options(mesh, plane_xyz, 3, &o, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  o.snap = 0.2;
  o.face_point_margin = -1.0;
  EXPECT(mtcut_mesh_cut_with_options(mesh, plane_xyz, 3, &o, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  o.face_point_margin = 0.5;
  o.struct_size = sizeof o + 8;
  EXPECT(mtcut_mesh_cut_with_options(mesh, plane_xyz, 3, &o, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  o.struct_size = sizeof o;
  UNTOUCHED(st.tets_cut == 0);

  EXPECT(mtcut_mesh_scalpel_sweep(NULL, start, end_same, NULL, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_scalpel_sweep(mesh, NULL, end_same, NULL, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mesh_scalpel_sweep(mesh, start, NULL, NULL, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  /* A blade that does not move sweeps nothing. */
  EXPECT(mtcut_mesh_scalpel_sweep(mesh, start, end_same, &o, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  {
    double advance = -1.0;
    const double nan_end[6] = {NAN, 0.5, 0.5, 2, 0.5, 0.5};
    EXPECT(mtcut_blade_advance(NULL, end_same, &advance), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_blade_advance(start, NULL, &advance), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_blade_advance(start, end_same, NULL), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_blade_advance(start, nan_end, &advance), MTCUT_STATUS_INVALID_ARGUMENT);
    UNTOUCHED(advance == -1.0);
  }
  o.scheme = 7;
  EXPECT(mtcut_mesh_scalpel_sweep(mesh, start, end_same, &o, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(st.tets_cut == 0);
  UNTOUCHED(mtcut_mesh_tet_count(mesh) == tets); /* no refused cut changed the mesh */

  {
    double xyz[3 * MTCUT_SWEEP_MAX_POINTS] = {0};
    size_t counts[2] = {0, 0}, n = 0;
    EXPECT(mtcut_scalpel_sweep_polygons(NULL, end_same, xyz, counts, &n),
           MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_scalpel_sweep_polygons(start, NULL, xyz, counts, &n), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_scalpel_sweep_polygons(start, end_same, NULL, counts, &n),
           MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_scalpel_sweep_polygons(start, end_same, xyz, NULL, &n),
           MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_scalpel_sweep_polygons(start, end_same, xyz, counts, NULL),
           MTCUT_STATUS_NULL_ARGUMENT);
    /* A blade that does not move sweeps nothing. */
    EXPECT(mtcut_scalpel_sweep_polygons(start, end_same, xyz, counts, &n),
           MTCUT_STATUS_INVALID_ARGUMENT);
    UNTOUCHED(n == 0 && counts[0] == 0 && counts[1] == 0 && xyz[0] == 0.0);
  }
}

static int cancel_at_once(void *user, double fraction) {
  (void)fraction;
  ++*(int *)user;
  return 1;
}

static void check_mt(const mtcut_mesh *mesh, const char *dir) {
  mtcut_mt *mt_sentinel = (mtcut_mt *)&failures;
  mtcut_mt *mt = mt_sentinel, *good = NULL;
  mtcut_mesh *mesh_sentinel = (mtcut_mesh *)&failures;
  mtcut_mesh *out = mesh_sentinel;
  mtcut_frontier *f_sentinel = (mtcut_frontier *)&failures;
  mtcut_frontier *frontier = f_sentinel, *good_frontier = NULL;
  mtcut_build_options bo;
  mtcut_extract_options eo;
  mtcut_extract_stats es;
  mtcut_frontier_update_stats fs;
  mtcut_mt_stats ms;
  mtcut_cut_stats st;
  double bad[9];
  char path[4096];
  int calls = 0;
  FILE *f;

  memset(&bo, 0, sizeof bo);
  EXPECT(mtcut_build_options_default(NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_build_options_default(&bo), MTCUT_STATUS_INVALID_ARGUMENT);
  bo.struct_size = sizeof bo;
  EXPECT(mtcut_build_options_default(&bo), MTCUT_STATUS_OK);

  EXPECT(mtcut_mt_build(NULL, &bo, &mt), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_build(mesh, &bo, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  bo.error_metric = 3;
  EXPECT(mtcut_mt_build(mesh, &bo, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
  bo.error_metric = MTCUT_ERROR_METRIC_VOLUME;
  bo.min_quality = 2.0;
  EXPECT(mtcut_mt_build(mesh, &bo, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
  bo.min_quality = 0.02;
  bo.boundary_tolerance = -1.0;
  EXPECT(mtcut_mt_build(mesh, &bo, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
  bo.boundary_tolerance = 0.005;
  bo.feature_angle_degrees = NAN;
  EXPECT(mtcut_mt_build(mesh, &bo, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
  bo.feature_angle_degrees = 30.0;
  bo.struct_size = 3;
  EXPECT(mtcut_mt_build(mesh, &bo, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
  bo.struct_size = sizeof bo;
  bo.progress_or_null = cancel_at_once;
  bo.user = &calls;
  EXPECT(mtcut_mt_build(mesh, &bo, &mt), MTCUT_STATUS_CANCELLED);
  UNTOUCHED(mt == mt_sentinel);
  if (calls != 1) {
    fprintf(stderr, "null_args.c:%d: the callback ran %d times, expected once\n", __LINE__, calls);
    failures++;
  }
  EXPECT(mtcut_mt_build(mesh, NULL, &good), MTCUT_STATUS_OK);
  if (good == NULL) {
    failures++;
    return;
  }

  path_in(path, sizeof path, dir, "cube.mt");
  EXPECT(mtcut_mt_save(NULL, path), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_save(good, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  path_in(path, sizeof path, dir, "no-such-dir/cube.mt");
  EXPECT(mtcut_mt_save(good, path), MTCUT_STATUS_IO_ERROR);
  EXPECT(mtcut_mt_load(NULL, &mt), MTCUT_STATUS_NULL_ARGUMENT);
  path_in(path, sizeof path, dir, "cube.mt");
  EXPECT(mtcut_mt_load(path, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_load(path, &mt), MTCUT_STATUS_IO_ERROR); /* not saved: no such file */
  path_in(path, sizeof path, dir, "bad.node"); /* written by check_files: not a model */
  EXPECT(mtcut_mt_load(path, &mt), MTCUT_STATUS_UNSUPPORTED_FORMAT);
  path_in(path, sizeof path, dir, "truncated.mt");
  f = fopen(path, "wb");
  if (f != NULL) {
    fwrite("MTCUTMT\0\1\0\0\0", 1, 12, f);
    fclose(f);
  }
  EXPECT(mtcut_mt_load(path, &mt), MTCUT_STATUS_PARSE_ERROR);
  UNTOUCHED(mt == mt_sentinel);
  mtcut_mt_free(NULL); /* allowed: nothing happens */

  memset(&ms, 0, sizeof ms);
  ms.struct_size = sizeof ms;
  EXPECT(mtcut_mt_statistics(NULL, &ms), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_statistics(good, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  ms.struct_size = sizeof ms * 2;
  EXPECT(mtcut_mt_statistics(good, &ms), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(ms.vertices == 0);

  memset(&st, 0, sizeof st);
  st.struct_size = sizeof st;
  EXPECT(mtcut_mt_cut(NULL, plane_xyz, 3, &st), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_cut(good, NULL, 3, &st), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_cut(good, plane_xyz, 2, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mt_cut(good, plane_xyz, SIZE_MAX, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  memcpy(bad, plane_xyz, sizeof bad);
  bad[4] = NAN;
  EXPECT(mtcut_mt_cut(good, bad, 3, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  st.struct_size = 1;
  EXPECT(mtcut_mt_cut(good, plane_xyz, 3, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(st.tets_cut == 0);

  {
    bool valid = false;
    char message[16] = "untouched";
    size_t length = 12345;
    EXPECT(mtcut_mt_validate(NULL, &valid, message, sizeof message, &length),
           MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_validate(good, NULL, message, sizeof message, &length),
           MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_validate(good, &valid, NULL, sizeof message, &length),
           MTCUT_STATUS_NULL_ARGUMENT);
    UNTOUCHED(!valid && strcmp(message, "untouched") == 0 && length == 12345);
  }

  EXPECT(mtcut_mt_component(NULL, 0, &mt), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_component(good, 0, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_component(good, 1, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mt_component(good, SIZE_MAX, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(mt == mt_sentinel);

  {
    const double lo[3] = {-1, -1, -1}, hi[3] = {0.5, 2, 2}, nan_lo[3] = {NAN, -1, -1};
    EXPECT(mtcut_mt_roi_box(NULL, lo, hi, &mt), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_roi_box(good, NULL, hi, &mt), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_roi_box(good, lo, NULL, &mt), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_roi_box(good, lo, hi, NULL), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_roi_box(good, nan_lo, hi, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
    EXPECT(mtcut_mt_roi_box(good, hi, lo, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
    EXPECT(mtcut_mt_roi_sphere(NULL, lo, 1.0, &mt), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_roi_sphere(good, NULL, 1.0, &mt), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_roi_sphere(good, lo, 1.0, NULL), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_mt_roi_sphere(good, lo, NAN, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
    EXPECT(mtcut_mt_roi_sphere(good, lo, 0.0, &mt), MTCUT_STATUS_INVALID_ARGUMENT);
    UNTOUCHED(mt == mt_sentinel);
  }

  EXPECT(mtcut_mt_extract_threshold(NULL, 0.0, &out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_extract_threshold(good, 0.0, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_extract_threshold(good, -1.0, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_mt_extract_threshold(good, NAN, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(out == mesh_sentinel);

  memset(&eo, 0, sizeof eo);
  EXPECT(mtcut_extract_options_default(NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_extract_options_default(&eo), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.struct_size = sizeof eo;
  EXPECT(mtcut_extract_options_default(&eo), MTCUT_STATUS_OK);
  memset(&es, 0, sizeof es);
  es.struct_size = sizeof es;
  EXPECT(mtcut_mt_extract(NULL, &eo, &es, &out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_mt_extract(good, &eo, &es, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  eo.focus = 3;
  EXPECT(mtcut_mt_extract(good, &eo, &es, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.focus = MTCUT_FOCUS_SPHERE;
  eo.focus_radius = -1.0;
  EXPECT(mtcut_mt_extract(good, &eo, &es, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.focus_radius = 0.5;
  eo.focus_center[1] = INFINITY;
  EXPECT(mtcut_mt_extract(good, &eo, &es, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.focus_center[1] = 0.0;
  eo.focus_threshold = -2.0;
  EXPECT(mtcut_mt_extract(good, &eo, &es, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.focus_threshold = 0.0;
  eo.focus = MTCUT_FOCUS_BOX;
  eo.focus_min[0] = 1.0; /* min above max */
  EXPECT(mtcut_mt_extract(good, &eo, &es, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.focus = MTCUT_FOCUS_NONE;
  eo.threshold = -1.0;
  EXPECT(mtcut_mt_extract(good, &eo, &es, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.threshold = 0.0;
  es.struct_size = 0;
  EXPECT(mtcut_mt_extract(good, &eo, &es, &out), MTCUT_STATUS_INVALID_ARGUMENT);
  es.struct_size = sizeof es;
  UNTOUCHED(out == mesh_sentinel && es.tets == 0);

  EXPECT(mtcut_frontier_new(NULL, &eo, &frontier), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_frontier_new(good, &eo, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  eo.threshold = NAN;
  EXPECT(mtcut_frontier_new(good, &eo, &frontier), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.threshold = 0.0;
  UNTOUCHED(frontier == f_sentinel);
  EXPECT(mtcut_frontier_new(good, NULL, &good_frontier), MTCUT_STATUS_OK);
  memset(&fs, 0, sizeof fs);
  fs.struct_size = sizeof fs;
  EXPECT(mtcut_frontier_update(NULL, &eo, &fs), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_frontier_update(good_frontier, NULL, &fs), MTCUT_STATUS_NULL_ARGUMENT);
  eo.budget = 1;
  eo.focus = 99;
  EXPECT(mtcut_frontier_update(good_frontier, &eo, &fs), MTCUT_STATUS_INVALID_ARGUMENT);
  eo.focus = MTCUT_FOCUS_NONE;
  fs.struct_size = 5;
  EXPECT(mtcut_frontier_update(good_frontier, &eo, &fs), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(fs.tets == 0);
  /* Every refusal above left the frontier at the input mesh. */
  UNTOUCHED(mtcut_frontier_tet_count(good_frontier) == mtcut_mesh_tet_count(mesh));
  EXPECT_ZERO(mtcut_frontier_tet_count(NULL));
  EXPECT(mtcut_frontier_mesh(NULL, &out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_frontier_mesh(good_frontier, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(out == mesh_sentinel);
  mtcut_frontier_free(NULL); /* allowed: nothing happens */
  mtcut_frontier_free(good_frontier);
  mtcut_mt_free(good);
}

/* The live (time-critical) model: every function refuses NULL handles and pointers, a
   wrong count or bad numbers, and leaves outputs and the model as they were. */
static void check_live(const mtcut_mesh *mesh) {
  mtcut_mt *mt = NULL;
  mtcut_live *live_sentinel = (mtcut_live *)&failures;
  mtcut_live *live = live_sentinel, *good = NULL;
  mtcut_mesh *mesh_sentinel = (mtcut_mesh *)&failures;
  mtcut_mesh *out = mesh_sentinel;
  mtcut_mt *mt_sentinel = (mtcut_mt *)&failures;
  mtcut_mt *mt_out = mt_sentinel;
  mtcut_pending_report report;
  mtcut_cut_stats st;
  double xyz[3 * 64], small[3];
  uint32_t tets[4 * 64], ids[64];
  /* A triangle across the cube at z = 0.5. */
  const double across[9] = {-1, -1, 0.5, 5, -1, 0.5, -1, 5, 0.5};
  size_t n;

  if (mtcut_mt_build(mesh, NULL, &mt) != MTCUT_STATUS_OK) {
    fprintf(stderr, "check_live: build: %s\n", mtcut_last_error_message());
    ++failures;
    return;
  }
  EXPECT(mtcut_live_new(NULL, NULL, &live), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_new(mt, NULL, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(live == live_sentinel);
  EXPECT(mtcut_live_new(mt, NULL, &good), MTCUT_STATUS_OK);
  mtcut_mt_free(mt); /* the live model keeps its own copy */

  EXPECT_ZERO(mtcut_live_vertex_count(NULL));
  EXPECT_ZERO(mtcut_live_tet_count(NULL));
  EXPECT_ZERO(mtcut_live_pending_cuts(NULL));
  n = mtcut_live_vertex_count(good);
  UNTOUCHED(n == 8 && mtcut_live_tet_count(good) == 6);

  EXPECT(mtcut_live_copy_positions(NULL, xyz, 64), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_copy_positions(good, NULL, 64), MTCUT_STATUS_NULL_ARGUMENT);
  small[0] = -7;
  EXPECT(mtcut_live_copy_positions(good, small, 1), MTCUT_STATUS_BUFFER_TOO_SMALL);
  UNTOUCHED(small[0] == -7);
  EXPECT(mtcut_live_copy_rest_positions(NULL, xyz, 64), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_copy_rest_positions(good, NULL, 64), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_copy_tets(NULL, tets, 64), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_copy_tets(good, NULL, 64), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_copy_mt_vertex_ids(NULL, ids, 64), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_copy_mt_vertex_ids(good, NULL, 64), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_copy_tets(good, tets, 64), MTCUT_STATUS_OK);
  EXPECT(mtcut_live_copy_mt_vertex_ids(good, ids, 64), MTCUT_STATUS_OK);

  EXPECT(mtcut_live_copy_positions(good, xyz, 64), MTCUT_STATUS_OK);
  EXPECT(mtcut_live_set_positions(NULL, xyz, n), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_set_positions(good, NULL, n), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_set_positions(good, xyz, n - 1), MTCUT_STATUS_INVALID_ARGUMENT);
  xyz[4] = NAN;
  EXPECT(mtcut_live_set_positions(good, xyz, n), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_live_copy_positions(good, xyz, 64), MTCUT_STATUS_OK);
  UNTOUCHED(xyz[4] == xyz[4]); /* still a number: the refusal changed nothing */

  memset(&st, 0, sizeof st);
  st.struct_size = sizeof st;
  EXPECT(mtcut_live_cut(NULL, across, 3, &st), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_cut(good, NULL, 3, &st), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_cut(good, across, 2, &st), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(mtcut_live_pending_cuts(good) == 0);
  EXPECT(mtcut_live_cut(good, across, 3, &st), MTCUT_STATUS_OK);
  UNTOUCHED(mtcut_live_pending_cuts(good) == 1 && st.tets_cut > 0);
  {
    /* A scalpel sweep: NULL ends, and a blade that does not move (nothing swept). */
    const double start[6] = {0.1, 0.2, -1.0, 0.1, 0.2, 2.0};
    const double end[6] = {0.8, 0.3, -1.0, 0.8, 0.3, 2.0};
    EXPECT(mtcut_live_scalpel_sweep(NULL, start, end, &st), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_live_scalpel_sweep(good, NULL, end, &st), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_live_scalpel_sweep(good, start, NULL, &st), MTCUT_STATUS_NULL_ARGUMENT);
    EXPECT(mtcut_live_scalpel_sweep(good, start, start, &st), MTCUT_STATUS_INVALID_ARGUMENT);
    UNTOUCHED(mtcut_live_pending_cuts(good) == 1);
  }

  EXPECT(mtcut_live_set_resolution(NULL, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_set_resolution(good, NULL), MTCUT_STATUS_PENDING_WORK);

  memset(&report, 0, sizeof report);
  report.struct_size = sizeof report;
  EXPECT(mtcut_live_process_pending(NULL, 0, 0.0, &report), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_process_pending(good, 0, -1.0, &report), MTCUT_STATUS_INVALID_ARGUMENT);
  EXPECT(mtcut_live_process_pending(good, 0, NAN, &report), MTCUT_STATUS_INVALID_ARGUMENT);
  UNTOUCHED(mtcut_live_pending_cuts(good) == 1);
  EXPECT(mtcut_live_process_pending(good, 0, 0.0, &report), MTCUT_STATUS_OK);
  UNTOUCHED(report.cuts_done == 1 && report.cuts_left == 0);
  EXPECT(mtcut_live_set_resolution(good, NULL), MTCUT_STATUS_OK);

  EXPECT(mtcut_live_mesh(NULL, &out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_mesh(good, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(out == mesh_sentinel);
  EXPECT(mtcut_live_mt(NULL, &mt_out), MTCUT_STATUS_NULL_ARGUMENT);
  EXPECT(mtcut_live_mt(good, NULL), MTCUT_STATUS_NULL_ARGUMENT);
  UNTOUCHED(mt_out == mt_sentinel);
  EXPECT(mtcut_live_mt(good, &mt_out), MTCUT_STATUS_OK);
  mtcut_mt_free(mt_out);

  mtcut_live_free(NULL); /* allowed: nothing happens */
  mtcut_live_free(good);
}

int main(int argc, char **argv) {
  mtcut_mesh *mesh = NULL;
  if (argc != 2) {
    fprintf(stderr, "usage: %s SCRATCH_DIR\n", argv[0]);
    return 2;
  }
  check_status_and_version();
  check_from_arrays();
  if (mtcut_mesh_from_arrays(cube_xyz, 8, cube_tets, 6, &mesh) != MTCUT_STATUS_OK) {
    fprintf(stderr, "the cube: %s\n", mtcut_last_error_message());
    return 1;
  }
  check_files(mesh, argv[1]);
  check_arrays_out(mesh);
  check_measures(mesh);
  check_attributes(mesh);
  check_mt(mesh, argv[1]);
  check_cut(mesh);
  check_live(mesh);
  mtcut_mesh_free(mesh);
  if (failures > 0) {
    fprintf(stderr, "null_args: %d failures\n", failures);
    return 1;
  }
  printf("null_args: every function refused NULL and invalid arguments cleanly\n");
  return 0;
}
