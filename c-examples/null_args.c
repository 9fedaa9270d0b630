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
  mtcut_mesh_free(mesh);
  if (failures > 0) {
    fprintf(stderr, "null_args: %d failures\n", failures);
    return 1;
  }
  printf("null_args: every function refused NULL and invalid arguments cleanly\n");
  return 0;
}
