/* Shared by the examples: writes a mesh as .vtu with a JSON sidecar (FILE.vtu.json) holding
 * what mtcut says the file holds - point and cell counts, volume, point and cell array
 * names - which check_vtu.py (VTK) and scripts/pvbatch-check.py (ParaView) compare with
 * what they read. C99 and C++17. Exits the program on failure (these are examples). The
 * functions are `static inline` so that a program using only some of them builds without
 * warnings. */
#ifndef MTCUT_EXAMPLE_SIDECAR_H
#define MTCUT_EXAMPLE_SIDECAR_H

#include <mtcut.h>

#include <stdio.h>
#include <stdlib.h>

static inline void mtcut_example_fail(const char *what) {
  fprintf(stderr, "%s: %s\n", what, mtcut_last_error_message());
  exit(1);
}

/* snprintf's result checked: a path that does not fit stops the program (and optimising
 * compilers do not warn of a truncation the program would not notice). */
static inline void mtcut_example_path(char *out, size_t size, const char *a, const char *b,
                                      const char *c) {
  if (snprintf(out, size, "%s%s%s", a, b, c) >= (int)size) {
    fprintf(stderr, "path too long: %s%s%s\n", a, b, c);
    exit(1);
  }
}

/* Writes VTU_PATH.json: what `mesh` holds, as mtcut reports it. */
static inline void mtcut_example_write_sidecar(const mtcut_mesh *mesh, const char *vtu_path) {
  char path[4096], column[256];
  const mtcut_location where[2] = {MTCUT_LOCATION_VERTEX, MTCUT_LOCATION_TET};
  const char *key[2] = {"point_arrays", "cell_arrays"};
  double volume = 0.0;
  size_t count = 0, i, w;
  FILE *f;

  if (mtcut_mesh_volume(mesh, &volume) != MTCUT_STATUS_OK) mtcut_example_fail("volume");
  mtcut_example_path(path, sizeof path, vtu_path, ".json", "");
  f = fopen(path, "w");
  if (f == NULL) {
    perror(path);
    exit(1);
  }
  fprintf(f, "{\"points\": %lu, \"cells\": %lu, \"volume\": %.17g",
          (unsigned long)mtcut_mesh_vertex_count(mesh), (unsigned long)mtcut_mesh_tet_count(mesh),
          volume);
  for (w = 0; w < 2; w++) {
    if (mtcut_mesh_attribute_count(mesh, where[w], &count) != MTCUT_STATUS_OK) {
      mtcut_example_fail("attribute count");
    }
    fprintf(f, ", \"%s\": [", key[w]);
    for (i = 0; i < count; i++) {
      if (mtcut_mesh_attribute_name(mesh, where[w], i, column, sizeof column, NULL) !=
          MTCUT_STATUS_OK) {
        mtcut_example_fail("attribute name");
      }
      fprintf(f, "%s\"%s\"", i ? ", " : "", column);
    }
    fprintf(f, "]");
  }
  fprintf(f, "}\n");
  if (fclose(f) != 0) {
    perror(path);
    exit(1);
  }
}

/* Writes DIR/NAME with mtcut's writer, and its sidecar DIR/NAME.json. */
static inline void mtcut_example_write_vtu(const mtcut_mesh *mesh, const char *dir, const char *name) {
  char path[4096];
  mtcut_example_path(path, sizeof path, dir, "/", name);
  if (mtcut_mesh_write_vtu(mesh, path) != MTCUT_STATUS_OK) mtcut_example_fail(path);
  mtcut_example_write_sidecar(mesh, path);
  printf("wrote %s\n", path);
}

#endif
