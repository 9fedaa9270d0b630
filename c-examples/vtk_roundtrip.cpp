// vtk_roundtrip: mtcut inside a VTK 9.1 pipeline. Reads a .vtu with VTK's reader, hands
// its points, tets, point data and cell data to mtcut as arrays, checks and measures the
// mesh there, with --cut cuts it through its middle, turns mtcut's mesh back into a
// vtkUnstructuredGrid with its point and cell data, writes it with VTK's writer, and reads
// that file back with VTK to check that nothing was lost: counts, every array (values too
// when not cut), and the volume VTK computes against mtcut's. With --cut it also writes
// the JSON sidecar OUT.vtu.json (sidecar.h) for the ParaView check.
//
// Usage: vtk_roundtrip IN.vtu OUT.vtu [--cut]
#include <mtcut.h>

#include "sidecar.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkTetra.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct MeshDeleter {
  void operator()(mtcut_mesh *m) const noexcept { mtcut_mesh_free(m); }
};
using Mesh = std::unique_ptr<mtcut_mesh, MeshDeleter>;

void check(mtcut_status status, const std::string &what) {
  if (status != MTCUT_STATUS_OK) {
    throw std::runtime_error(what + ": " + mtcut_status_message(status) + ": " +
                             mtcut_last_error_message());
  }
}

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::string &path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  if (reader->GetErrorCode() != 0 || reader->GetOutput() == nullptr) {
    throw std::runtime_error(path + ": VTK cannot read it");
  }
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  return grid;
}

// Numeric VTK arrays with a name and 1 to MTCUT_MAX_COMPONENTS components become mtcut
// attribute columns; others are reported and left out.
void arrays_to_mtcut(vtkFieldData *data, mtcut_mesh *mesh, mtcut_location where, size_t rows) {
  for (int k = 0; k < data->GetNumberOfArrays(); k++) {
    vtkDataArray *array = vtkDataArray::SafeDownCast(data->GetAbstractArray(k));
    const int nc = array ? array->GetNumberOfComponents() : 0;
    if (!array || !array->GetName() || nc < 1 || nc > static_cast<int>(MTCUT_MAX_COMPONENTS) ||
        static_cast<size_t>(array->GetNumberOfTuples()) != rows) {
      std::printf("  (array %d left out: not a named numeric array of 1-%d components)\n", k,
                  static_cast<int>(MTCUT_MAX_COMPONENTS));
      continue;
    }
    std::vector<double> values(rows * nc);
    for (size_t i = 0; i < rows; i++) array->GetTuple(static_cast<vtkIdType>(i), &values[i * nc]);
    check(mtcut_mesh_set_attribute(mesh, where, array->GetName(), values.data(), rows,
                                   static_cast<size_t>(nc)),
          std::string("set attribute ") + array->GetName());
  }
}

// VTK grid -> mtcut mesh: tets only (another cell type is an error naming it).
Mesh to_mtcut(vtkUnstructuredGrid *grid) {
  const vtkIdType np = grid->GetNumberOfPoints(), nc = grid->GetNumberOfCells();
  std::vector<double> xyz(3 * static_cast<size_t>(np));
  for (vtkIdType i = 0; i < np; i++) grid->GetPoint(i, &xyz[3 * i]);
  std::vector<uint32_t> tets;
  tets.reserve(4 * static_cast<size_t>(nc));
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < nc; c++) {
    if (grid->GetCellType(c) != VTK_TETRA) {
      throw std::runtime_error("cell " + std::to_string(c) + " has VTK cell type " +
                               std::to_string(grid->GetCellType(c)) + ", not a tetrahedron (10)");
    }
    grid->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < 4; k++) tets.push_back(static_cast<uint32_t>(ids->GetId(k)));
  }
  mtcut_mesh *raw = nullptr;
  check(mtcut_mesh_from_arrays(xyz.data(), static_cast<size_t>(np), tets.data(),
                               static_cast<size_t>(nc), &raw),
        "mesh from VTK arrays");
  Mesh mesh(raw);
  arrays_to_mtcut(grid->GetPointData(), mesh.get(), MTCUT_LOCATION_VERTEX, static_cast<size_t>(np));
  arrays_to_mtcut(grid->GetCellData(), mesh.get(), MTCUT_LOCATION_TET, static_cast<size_t>(nc));
  return mesh;
}

void mtcut_to_arrays(const mtcut_mesh *mesh, mtcut_location where, size_t rows, vtkFieldData *out) {
  size_t count = 0;
  check(mtcut_mesh_attribute_count(mesh, where, &count), "attribute count");
  for (size_t i = 0; i < count; i++) {
    size_t length = 0, nc = 0;
    mtcut_status s = mtcut_mesh_attribute_name(mesh, where, i, nullptr, 0, &length);
    if (s != MTCUT_STATUS_BUFFER_TOO_SMALL) check(s, "attribute name length");
    std::string name(length, '\0');
    check(mtcut_mesh_attribute_name(mesh, where, i, name.data(), length + 1, nullptr),
          "attribute name");
    check(mtcut_mesh_attribute_components(mesh, where, name.c_str(), &nc), "components of " + name);
    vtkNew<vtkDoubleArray> array;
    array->SetName(name.c_str());
    array->SetNumberOfComponents(static_cast<int>(nc));
    array->SetNumberOfTuples(static_cast<vtkIdType>(rows));
    check(mtcut_mesh_copy_attribute(mesh, where, name.c_str(), array->GetPointer(0), rows * nc),
          "copy " + name);
    out->AddArray(array);
  }
}

// mtcut mesh -> VTK grid, with point and cell data.
vtkSmartPointer<vtkUnstructuredGrid> to_vtk(const mtcut_mesh *mesh) {
  const size_t nv = mtcut_mesh_vertex_count(mesh), nt = mtcut_mesh_tet_count(mesh);
  std::vector<double> xyz(3 * nv);
  std::vector<uint32_t> tets(4 * nt);
  check(mtcut_mesh_copy_vertices(mesh, xyz.data(), nv), "copy vertices");
  check(mtcut_mesh_copy_tets(mesh, tets.data(), nt), "copy tets");
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(nv));
  for (size_t i = 0; i < nv; i++) points->SetPoint(static_cast<vtkIdType>(i), &xyz[3 * i]);
  vtkNew<vtkCellArray> cells;
  for (size_t t = 0; t < nt; t++) {
    const vtkIdType ids[4] = {tets[4 * t], tets[4 * t + 1], tets[4 * t + 2], tets[4 * t + 3]};
    cells->InsertNextCell(4, ids);
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->SetCells(VTK_TETRA, cells);
  mtcut_to_arrays(mesh, MTCUT_LOCATION_VERTEX, nv, grid->GetPointData());
  mtcut_to_arrays(mesh, MTCUT_LOCATION_TET, nt, grid->GetCellData());
  return grid;
}

double vtk_volume(vtkUnstructuredGrid *grid) {
  double sum = 0.0, p[4][3];
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); c++) {
    grid->GetCellPoints(c, ids);
    for (int k = 0; k < 4; k++) grid->GetPoint(ids->GetId(k), p[k]);
    // vtkTetra::ComputeVolume is signed; mtcut's tets are positive (VTK's orientation).
    sum += vtkTetra::ComputeVolume(p[0], p[1], p[2], p[3]);
  }
  return sum;
}

// Every array written (`a`, `count` of them: as many as mtcut holds) is in the original
// (`b`) with the same components and values.
void same_arrays(vtkFieldData *a, vtkFieldData *b, size_t count, const char *what) {
  if (static_cast<size_t>(a->GetNumberOfArrays()) != count) {
    throw std::runtime_error(std::string(what) + ": VTK reads another number of arrays");
  }
  for (int k = 0; k < a->GetNumberOfArrays(); k++) {
    vtkDataArray *x = vtkDataArray::SafeDownCast(a->GetAbstractArray(k));
    vtkDataArray *y = x ? b->GetArray(x->GetName()) : nullptr;
    if (!x || !y || x->GetNumberOfComponents() != y->GetNumberOfComponents() ||
        x->GetNumberOfTuples() != y->GetNumberOfTuples()) {
      throw std::runtime_error(std::string(what) + ": array " + std::to_string(k) + " differs");
    }
    for (vtkIdType i = 0; i < x->GetNumberOfTuples(); i++) {
      for (int c = 0; c < x->GetNumberOfComponents(); c++) {
        if (x->GetComponent(i, c) != y->GetComponent(i, c)) {
          throw std::runtime_error(std::string(what) + ": values of " + x->GetName() + " differ");
        }
      }
    }
  }
}

// After a cut: every array of the original (`b`) is in the output (`a`) with the same
// components and one row per element of the output; the output has `extra` more arrays
// (the cut's own column).
void same_names(vtkFieldData *a, vtkFieldData *b, vtkIdType rows, int extra, const char *what) {
  if (a->GetNumberOfArrays() != b->GetNumberOfArrays() + extra) {
    throw std::runtime_error(std::string(what) + ": another number of arrays after the cut");
  }
  for (int k = 0; k < b->GetNumberOfArrays(); k++) {
    vtkDataArray *y = vtkDataArray::SafeDownCast(b->GetAbstractArray(k));
    vtkDataArray *x = y ? a->GetArray(y->GetName()) : nullptr;
    if (!x || x->GetNumberOfComponents() != y->GetNumberOfComponents() ||
        x->GetNumberOfTuples() != rows) {
      throw std::runtime_error(std::string(what) + ": array " + std::to_string(k) +
                               " lost or resized by the cut");
    }
  }
}

// Cuts the mesh through the middle of its bounding box by a slightly tilted plane (a
// square larger than the mesh), printing the statistics.
void cut_through_middle(mtcut_mesh *mesh) {
  double lo[3], hi[3];
  check(mtcut_mesh_bounding_box(mesh, lo, hi), "bounding box");
  const double c[3] = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  const double r = (hi[0] - lo[0]) + (hi[1] - lo[1]) + (hi[2] - lo[2]);
  // Corners c + a u + b v, with u along x and v along y tilted a little towards z.
  const double u[3] = {1, 0, 0.1}, v[3] = {0, 1, 0.05};
  const double ab[4][2] = {{-r, -r}, {r, -r}, {r, r}, {-r, r}};
  double square[12];
  for (int k = 0; k < 4; k++) {
    for (int d = 0; d < 3; d++) square[3 * k + d] = c[d] + ab[k][0] * u[d] + ab[k][1] * v[d];
  }
  mtcut_cut_stats stats;
  std::memset(&stats, 0, sizeof stats);
  stats.struct_size = sizeof stats;
  check(mtcut_mesh_cut(mesh, square, 4, &stats), "cut");
  std::printf("cut: %zu tets tested, %zu cut, %zu created, %zu vertices added; %zu tets, %zu "
              "component(s); %.3f ms\n",
              stats.tets_tested, stats.tets_cut, stats.tets_created, stats.vertices_added,
              stats.tets_after, stats.components, 1e3 * stats.seconds_cut);
  if (stats.tets_cut == 0 || stats.components < 2) {
    throw std::runtime_error("the cut through the middle did not separate the mesh");
  }
}

}  // namespace

int main(int argc, char **argv) {
  const bool cut = argc == 4 && std::strcmp(argv[3], "--cut") == 0;
  if (argc != 3 && !cut) {
    std::fprintf(stderr, "usage: %s IN.vtu OUT.vtu [--cut]\n", argv[0]);
    return 2;
  }
  try {
    vtkSmartPointer<vtkUnstructuredGrid> input = read_vtu(argv[1]);
    Mesh mesh = to_mtcut(input);
    bool valid = false;
    char message[512];
    double volume = 0.0;
    check(mtcut_mesh_validate(mesh.get(), &valid, message, sizeof message, nullptr), "validate");
    check(mtcut_mesh_volume(mesh.get(), &volume), "volume");
    std::printf("%s: %lld points, %lld tets, %d point arrays, %d cell arrays; mtcut: %s, volume %.9g\n",
                argv[1], static_cast<long long>(input->GetNumberOfPoints()),
                static_cast<long long>(input->GetNumberOfCells()),
                input->GetPointData()->GetNumberOfArrays(),
                input->GetCellData()->GetNumberOfArrays(), message, volume);
    if (!valid) throw std::runtime_error("mtcut finds the mesh invalid");
    if (cut) {
      cut_through_middle(mesh.get());
      check(mtcut_mesh_validate(mesh.get(), &valid, message, sizeof message, nullptr), "validate");
      double after = 0.0;
      check(mtcut_mesh_volume(mesh.get(), &after), "volume");
      if (!valid || std::fabs(after - volume) > 1e-9 * volume) {
        throw std::runtime_error(std::string("after the cut: ") + message);
      }
      volume = after;
    }

    vtkSmartPointer<vtkUnstructuredGrid> output = to_vtk(mesh.get());
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetFileName(argv[2]);
    writer->SetInputData(output);
    if (writer->Write() != 1) throw std::runtime_error(std::string(argv[2]) + ": VTK cannot write it");

    vtkSmartPointer<vtkUnstructuredGrid> back = read_vtu(argv[2]);
    const double vtk_vol = vtk_volume(back);
    std::printf("%s: %lld points, %lld tets, volume by VTK %.9g\n", argv[2],
                static_cast<long long>(back->GetNumberOfPoints()),
                static_cast<long long>(back->GetNumberOfCells()), vtk_vol);
    if (static_cast<size_t>(back->GetNumberOfPoints()) != mtcut_mesh_vertex_count(mesh.get()) ||
        static_cast<size_t>(back->GetNumberOfCells()) != mtcut_mesh_tet_count(mesh.get())) {
      throw std::runtime_error("VTK reads other counts than mtcut wrote");
    }
    if (std::fabs(vtk_vol - volume) > 1e-12 * std::fabs(volume)) {
      throw std::runtime_error("VTK's volume differs from mtcut's");
    }
    size_t vertex_columns = 0, tet_columns = 0;
    check(mtcut_mesh_attribute_count(mesh.get(), MTCUT_LOCATION_VERTEX, &vertex_columns), "count");
    check(mtcut_mesh_attribute_count(mesh.get(), MTCUT_LOCATION_TET, &tet_columns), "count");
    if (cut) {
      same_names(back->GetPointData(), input->GetPointData(), back->GetNumberOfPoints(), 0,
                 "point data");
      same_names(back->GetCellData(), input->GetCellData(), back->GetNumberOfCells(), 1,
                 "cell data");
      mtcut_example_write_sidecar(mesh.get(), argv[2]);
      std::printf("cut through mtcut: counts, volume and arrays agree\n");
    } else {
      same_arrays(back->GetPointData(), input->GetPointData(), vertex_columns, "point data");
      same_arrays(back->GetCellData(), input->GetCellData(), tet_columns, "cell data");
      std::printf("round trip through mtcut: counts, volume and every array agree\n");
    }
  } catch (const std::exception &e) {
    std::fprintf(stderr, "vtk_roundtrip: %s\n", e.what());
    return 1;
  }
  return 0;
}
