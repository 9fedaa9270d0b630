// cpp_wrapper: the C API from C++17, the way a FEM code would hold it: handles in
// std::unique_ptr, failures turned into exceptions carrying the library's message, arrays
// in std::vector. Reads the mesh file given on the command line, tags each tet with its
// volume as an attribute, and checks that the per-tet volumes add up to the total.
//
// Usage: cpp_wrapper MESH_FILE
#include <mtcut.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct MeshDeleter {
  void operator()(mtcut_mesh *m) const noexcept { mtcut_mesh_free(m); }
};
using Mesh = std::unique_ptr<mtcut_mesh, MeshDeleter>;

// Throws on a failed call, with the status's description and the specific message.
void check(mtcut_status status, const char *what) {
  if (status != MTCUT_STATUS_OK) {
    throw std::runtime_error(std::string(what) + ": " + mtcut_status_message(status) + ": " +
                             mtcut_last_error_message());
  }
}

Mesh read(const std::string &path) {
  mtcut_mesh *raw = nullptr;
  check(mtcut_mesh_read(path.c_str(), &raw), "read");
  return Mesh(raw);
}

std::vector<std::string> attribute_names(const mtcut_mesh *mesh, mtcut_location where) {
  size_t count = 0;
  check(mtcut_mesh_attribute_count(mesh, where, &count), "attribute count");
  std::vector<std::string> names;
  for (size_t i = 0; i < count; i++) {
    size_t length = 0;
    // A NULL buffer with capacity 0 asks for the length (and reports "buffer too small").
    mtcut_status s = mtcut_mesh_attribute_name(mesh, where, i, nullptr, 0, &length);
    if (s != MTCUT_STATUS_BUFFER_TOO_SMALL) check(s, "attribute name length");
    std::string name(length, '\0');
    check(mtcut_mesh_attribute_name(mesh, where, i, name.data(), length + 1, nullptr),
          "attribute name");
    names.push_back(name);
  }
  return names;
}

double tet_volume(const std::vector<double> &xyz, const uint32_t *t) {
  auto p = [&](int k, int c) { return xyz[3 * t[k] + c]; };
  double u[3], v[3], w[3];
  for (int c = 0; c < 3; c++) {
    u[c] = p(1, c) - p(0, c);
    v[c] = p(2, c) - p(0, c);
    w[c] = p(3, c) - p(0, c);
  }
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s MESH_FILE\n", argv[0]);
    return 2;
  }
  try {
    Mesh mesh = read(argv[1]);
    const size_t nv = mtcut_mesh_vertex_count(mesh.get());
    const size_t nt = mtcut_mesh_tet_count(mesh.get());
    std::vector<double> xyz(3 * nv);
    std::vector<uint32_t> tets(4 * nt);
    check(mtcut_mesh_copy_vertices(mesh.get(), xyz.data(), nv), "copy vertices");
    check(mtcut_mesh_copy_tets(mesh.get(), tets.data(), nt), "copy tets");

    std::vector<double> volumes(nt);
    double sum = 0.0;
    for (size_t t = 0; t < nt; t++) {
      volumes[t] = tet_volume(xyz, &tets[4 * t]);
      if (!(volumes[t] > 0.0)) throw std::runtime_error("a tet is not positively oriented");
      sum += volumes[t];
    }
    check(mtcut_mesh_set_attribute(mesh.get(), MTCUT_LOCATION_TET, "volume", volumes.data(), nt, 1),
          "set attribute");
    double total = 0.0;
    check(mtcut_mesh_volume(mesh.get(), &total), "volume");
    if (std::fabs(total - sum) > 1e-9 * std::fabs(total)) {
      throw std::runtime_error("the per-tet volumes do not add up to the total");
    }
    std::printf("%s: %zu vertices, %zu tets, volume %.6g; tet attributes:", argv[1], nv, nt, total);
    for (const std::string &name : attribute_names(mesh.get(), MTCUT_LOCATION_TET)) {
      std::printf(" %s", name.c_str());
    }
    std::printf("\n");

    // A refused call throws with a message naming the function and the argument.
    try {
      check(mtcut_mesh_volume(mesh.get(), nullptr), "volume");
      return 1;
    } catch (const std::runtime_error &e) {
      std::printf("refused as expected: %s\n", e.what());
    }
  } catch (const std::exception &e) {
    std::fprintf(stderr, "cpp_wrapper: %s\n", e.what());
    return 1;
  }
  return 0;
}
