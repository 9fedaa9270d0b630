/* The smallest mtcut program: one tet from arrays, its volume. Exits 0 when the volume is
 * 1/6 and the library's version is the header's. */
#include <mtcut.h>

#include <stdio.h>
#include <string.h>

int main(void) {
  static const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const uint32_t tet[4] = {0, 1, 2, 3};
  mtcut_mesh *mesh = NULL;
  double volume = 0.0;
  mtcut_status s = mtcut_mesh_from_arrays(xyz, 4, tet, 1, &mesh);
  if (s == MTCUT_STATUS_OK) s = mtcut_mesh_volume(mesh, &volume);
  mtcut_mesh_free(mesh);
  if (s != MTCUT_STATUS_OK) {
    fprintf(stderr, "app: %s\n", mtcut_last_error_message());
    return 1;
  }
  printf("mtcut %s: one tet, volume %.17g\n", mtcut_version(), volume);
  return (volume == 1.0 / 6.0 && strcmp(mtcut_version(), MTCUT_VERSION_STRING) == 0) ? 0 : 1;
}
