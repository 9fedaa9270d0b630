// Shared by the C++17 examples (tetgen_mt, live_scalpel): mtcut's handles held in
// std::unique_ptr, failed calls and surprises turned into exceptions carrying the
// library's message, and the few queries every example checks its results with. Header
// only; everything in namespace mtcut_example.
#ifndef MTCUT_EXAMPLE_HANDLES_HPP
#define MTCUT_EXAMPLE_HANDLES_HPP

#include <mtcut.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

namespace mtcut_example {

struct MeshDeleter {
  void operator()(mtcut_mesh *m) const noexcept { mtcut_mesh_free(m); }
};
struct MtDeleter {
  void operator()(mtcut_mt *m) const noexcept { mtcut_mt_free(m); }
};
struct FrontierDeleter {
  void operator()(mtcut_frontier *f) const noexcept { mtcut_frontier_free(f); }
};
struct LiveDeleter {
  void operator()(mtcut_live *l) const noexcept { mtcut_live_free(l); }
};
using Mesh = std::unique_ptr<mtcut_mesh, MeshDeleter>;
using Mt = std::unique_ptr<mtcut_mt, MtDeleter>;
using Frontier = std::unique_ptr<mtcut_frontier, FrontierDeleter>;
using Live = std::unique_ptr<mtcut_live, LiveDeleter>;

// Throws on a failed call, with the status's description and the specific message.
inline void check(mtcut_status status, const std::string &what) {
  if (status != MTCUT_STATUS_OK) {
    throw std::runtime_error(what + ": " + mtcut_status_message(status) + ": " +
                             mtcut_last_error_message());
  }
}

inline void verify(bool cond, const std::string &what) {
  if (!cond) throw std::runtime_error("unexpected result: " + what);
}

inline double volume(const mtcut_mesh *m) {
  double v = 0.0;
  check(mtcut_mesh_volume(m, &v), "volume");
  return v;
}

inline size_t components(const mtcut_mesh *m) {
  size_t c = 0;
  check(mtcut_mesh_component_count(m, &c), "components");
  return c;
}

inline void verify_valid(const mtcut_mesh *m, const std::string &what) {
  bool valid = false;
  char message[512];
  check(mtcut_mesh_validate(m, &valid, message, sizeof message, nullptr), "validate");
  verify(valid, what + ": " + message);
}

inline mtcut_mt_stats statistics(const mtcut_mt *mt) {
  mtcut_mt_stats s;
  std::memset(&s, 0, sizeof s);
  s.struct_size = sizeof s;
  check(mtcut_mt_statistics(mt, &s), "statistics");
  return s;
}

}  // namespace mtcut_example

#endif
