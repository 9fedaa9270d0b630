/* mesh_basics: the mtcut C API on meshes, in plain C99.
 *
 * Builds a unit cube split into six tets from arrays, validates and measures it, attaches
 * per-vertex and per-tet attributes and reads them back, finds and extracts the
 * components of two cubes, writes a mesh and reads it back, then reads the mesh file given
 * on the command line and prints its statistics. Every result is checked: the program
 * exits with 1 on the first surprise, so ctest can run it.
 *
 * Usage: mesh_basics MESH_FILE OUTPUT_DIR
 */
#include <mtcut.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Stops on a failed call, printing the status and the library's message. */
#define CHECK(call)                                                                     \
  do {                                                                                  \
    mtcut_status status_ = (call);                                                      \
    if (status_ != MTCUT_STATUS_OK) {                                                   \
      fprintf(stderr, "%s:%d: %s: %s\n  %s\n", __FILE__, __LINE__, #call,               \
              mtcut_status_message(status_), mtcut_last_error_message());               \
      exit(1);                                                                          \
    }                                                                                   \
  } while (0)

/* Stops when a result is not what the geometry says it must be. */
#define VERIFY(cond)                                                           \
  do {                                                                         \
    if (!(cond)) {                                                             \
      fprintf(stderr, "%s:%d: unexpected result: %s\n", __FILE__, __LINE__, #cond); \
      exit(1);                                                                 \
    }                                                                          \
  } while (0)

static int close_to(double a, double b) { return fabs(a - b) <= 1e-12 * (1.0 + fabs(b)); }

/* A unit cube: vertex i at (i&1, (i>>1)&1, (i>>2)&1), six tets around the diagonal 0-7
 * (Kuhn's subdivision). Half of them are listed with negative orientation: mtcut
 * re-orients them on the way in. */
static const double cube_xyz[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,
                                    0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
static const uint32_t cube_tets[24] = {0, 1, 3, 7, 0, 1, 5, 7, 0, 2, 3, 7,
                                       0, 2, 6, 7, 0, 4, 5, 7, 0, 4, 6, 7};

/* Prints what a host usually wants to know about a mesh. */
static void print_statistics(const char *label, const mtcut_mesh *mesh) {
  bool valid = false;
  char message[256];
  size_t faces = 0, components = 0;
  double volume = 0, area = 0, lo[3], hi[3];
  mtcut_quality q;

  CHECK(mtcut_mesh_validate(mesh, &valid, message, sizeof message, NULL));
  CHECK(mtcut_mesh_volume(mesh, &volume));
  CHECK(mtcut_mesh_bounding_box(mesh, lo, hi));
  CHECK(mtcut_mesh_boundary(mesh, &faces, &area));
  CHECK(mtcut_mesh_component_count(mesh, &components));
  q.struct_size = sizeof q; /* versioned struct: say which version this program knows */
  CHECK(mtcut_mesh_quality(mesh, &q));

  printf("%s: %lu vertices, %lu tets, %s\n", label,
         (unsigned long)mtcut_mesh_vertex_count(mesh), (unsigned long)mtcut_mesh_tet_count(mesh),
         message);
  printf("  volume %.6g, bounding box (%.4g %.4g %.4g)-(%.4g %.4g %.4g)\n", volume, lo[0], lo[1],
         lo[2], hi[0], hi[1], hi[2]);
  printf("  boundary: %lu triangles, area %.6g; %lu component(s)\n", (unsigned long)faces, area,
         (unsigned long)components);
  printf("  dihedral angles %.2f..%.2f deg, aspect ratio mean %.3f max %.3f, %lu slivers\n",
         q.min_dihedral_deg, q.max_dihedral_deg, q.mean_aspect_ratio, q.max_aspect_ratio,
         (unsigned long)q.tets_below_5deg);
  VERIFY(valid);
  VERIFY(q.tets == mtcut_mesh_tet_count(mesh));
}

/* The cube: arrays in, checked, measured, arrays out. */
static mtcut_mesh *cube(void) {
  mtcut_mesh *mesh = NULL;
  double xyz[24], volume = 0, area = 0;
  uint32_t tets[24];
  size_t faces = 0;

  CHECK(mtcut_mesh_from_arrays(cube_xyz, 8, cube_tets, 6, &mesh));
  print_statistics("cube", mesh);
  CHECK(mtcut_mesh_volume(mesh, &volume));
  CHECK(mtcut_mesh_boundary(mesh, &faces, &area));
  VERIFY(close_to(volume, 1.0) && faces == 12 && close_to(area, 6.0));

  CHECK(mtcut_mesh_copy_vertices(mesh, xyz, 8));
  CHECK(mtcut_mesh_copy_tets(mesh, tets, 6));
  VERIFY(memcmp(xyz, cube_xyz, sizeof xyz) == 0);
  /* The first tet was positive and is kept as given; the second was re-oriented. */
  VERIFY(memcmp(tets, cube_tets, 4 * sizeof tets[0]) == 0);
  VERIFY(memcmp(tets + 4, cube_tets + 4, 4 * sizeof tets[0]) != 0);
  return mesh;
}

/* Attribute columns: a scalar and a vector per vertex, a material id per tet. */
static void attributes(mtcut_mesh *mesh) {
  double temperature[8], displacement[24], material[6], back[24];
  size_t count = 0, components = 0, length = 0, i;
  char name[64];

  for (i = 0; i < 8; i++) {
    temperature[i] = 20.0 + cube_xyz[3 * i + 2] * 80.0; /* hot on top */
    displacement[3 * i + 0] = 0.0;
    displacement[3 * i + 1] = 0.0;
    displacement[3 * i + 2] = -0.01 * cube_xyz[3 * i + 2];
  }
  for (i = 0; i < 6; i++) material[i] = (double)(i % 2);
  CHECK(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "temperature", temperature, 8, 1));
  CHECK(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_VERTEX, "displacement", displacement, 8, 3));
  CHECK(mtcut_mesh_set_attribute(mesh, MTCUT_LOCATION_TET, "material", material, 6, 1));

  CHECK(mtcut_mesh_attribute_count(mesh, MTCUT_LOCATION_VERTEX, &count));
  VERIFY(count == 2);
  printf("vertex attributes:");
  for (i = 0; i < count; i++) {
    CHECK(mtcut_mesh_attribute_name(mesh, MTCUT_LOCATION_VERTEX, i, name, sizeof name, &length));
    CHECK(mtcut_mesh_attribute_components(mesh, MTCUT_LOCATION_VERTEX, name, &components));
    printf(" %s (%lu)", name, (unsigned long)components);
  }
  printf("\n");
  CHECK(mtcut_mesh_attribute_components(mesh, MTCUT_LOCATION_VERTEX, "displacement", &components));
  VERIFY(components == 3);
  CHECK(mtcut_mesh_copy_attribute(mesh, MTCUT_LOCATION_VERTEX, "displacement", back, 24));
  VERIFY(memcmp(back, displacement, sizeof displacement) == 0);
  CHECK(mtcut_mesh_copy_attribute(mesh, MTCUT_LOCATION_TET, "material", back, 24));
  VERIFY(memcmp(back, material, sizeof material) == 0);
}

/* Two cubes side by side: two components, each extracted with its attribute rows. */
static void components(void) {
  double xyz[48], id[16], back[8], volume = 0;
  uint32_t tets[48];
  size_t count = 0, i;
  mtcut_mesh *both = NULL, *second = NULL;

  for (i = 0; i < 24; i++) {
    xyz[i] = cube_xyz[i];
    xyz[24 + i] = cube_xyz[i] + (i % 3 == 0 ? 2.0 : 0.0);
    tets[i] = cube_tets[i];
    tets[24 + i] = cube_tets[i] + 8;
  }
  for (i = 0; i < 16; i++) id[i] = (double)i;
  CHECK(mtcut_mesh_from_arrays(xyz, 16, tets, 12, &both));
  CHECK(mtcut_mesh_set_attribute(both, MTCUT_LOCATION_VERTEX, "id", id, 16, 1));
  CHECK(mtcut_mesh_component_count(both, &count));
  VERIFY(count == 2);
  CHECK(mtcut_mesh_extract_component(both, 1, &second));
  CHECK(mtcut_mesh_volume(second, &volume));
  CHECK(mtcut_mesh_copy_attribute(second, MTCUT_LOCATION_VERTEX, "id", back, 8));
  VERIFY(mtcut_mesh_vertex_count(second) == 8 && close_to(volume, 1.0));
  VERIFY(back[0] == 8.0 && back[7] == 15.0);
  printf("two cubes: %lu components; the second has %lu tets, volume %g\n", (unsigned long)count,
         (unsigned long)mtcut_mesh_tet_count(second), volume);
  mtcut_mesh_free(second);
  mtcut_mesh_free(both);
}

/* A deformed copy: moving vertices can invert tets, and validation says so. */
static void deformation(const mtcut_mesh *mesh) {
  mtcut_mesh *copy = NULL;
  double xyz[24];
  bool valid = true;
  size_t length = 0;
  char *message;

  CHECK(mtcut_mesh_clone(mesh, &copy));
  memcpy(xyz, cube_xyz, sizeof xyz);
  xyz[21] = xyz[22] = xyz[23] = -1.0; /* vertex 7 pushed through the opposite corner */
  CHECK(mtcut_mesh_set_vertices(copy, xyz, 8));
  /* Ask for the message's length first, then fetch it whole. */
  CHECK(mtcut_mesh_validate(copy, &valid, NULL, 0, &length));
  message = malloc(length + 1);
  VERIFY(message != NULL);
  CHECK(mtcut_mesh_validate(copy, &valid, message, length + 1, NULL));
  printf("deformed copy: %s\n", message);
  VERIFY(!valid && strlen(message) == length);
  free(message);
  mtcut_mesh_free(copy);
}

/* Files: write the cube as TetGen .node/.ele and as .vtu (with its attributes, for
 * ParaView) and read both back; then the user's file. */
static void files(const mtcut_mesh *mesh, const char *input, const char *dir) {
  char path[4096];
  mtcut_mesh *back = NULL, *user = NULL;
  double material[6], expected[6];
  size_t count = 0;

  snprintf(path, sizeof path, "%s/cube.node", dir);
  CHECK(mtcut_mesh_write(mesh, path));
  CHECK(mtcut_mesh_read(path, &back));
  VERIFY(mtcut_mesh_tet_count(back) == 6 && mtcut_mesh_vertex_count(back) == 8);
  mtcut_mesh_free(back);

  snprintf(path, sizeof path, "%s/cube.vtu", dir);
  CHECK(mtcut_mesh_write_vtu(mesh, path));
  CHECK(mtcut_mesh_read(path, &back));
  CHECK(mtcut_mesh_attribute_count(back, MTCUT_LOCATION_VERTEX, &count));
  VERIFY(count == 2);
  CHECK(mtcut_mesh_copy_attribute(back, MTCUT_LOCATION_TET, "material", material, 6));
  CHECK(mtcut_mesh_copy_attribute(mesh, MTCUT_LOCATION_TET, "material", expected, 6));
  VERIFY(memcmp(material, expected, sizeof material) == 0);
  printf("wrote %s (point and cell data) and read it back\n", path);
  mtcut_mesh_free(back);

  CHECK(mtcut_mesh_read(input, &user));
  print_statistics(input, user);
  mtcut_mesh_free(user);
}

int main(int argc, char **argv) {
  mtcut_mesh *mesh;
  if (argc != 3) {
    fprintf(stderr, "usage: %s MESH_FILE OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  printf("mtcut %s (header %s)\n", mtcut_version(), MTCUT_VERSION_STRING);
  mesh = cube();
  attributes(mesh);
  components();
  deformation(mesh);
  files(mesh, argv[1], argv[2]);
  mtcut_mesh_free(mesh);
  return 0;
}
