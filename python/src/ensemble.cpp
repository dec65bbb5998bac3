// Ensembles from Python: a study (a scene file's text with its [ensemble] table) run on every core; its
// table comes back as NumPy columns, one (R,) array per column of the same table `tumble ensemble` writes.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "tumble/io/ensemble.hpp"
#include "tumble/study/runs.hpp"

namespace py = pybind11;

namespace tumble::python {
namespace {

py::dict run_study(const std::string& text, const std::filesystem::path& path, int threads) {
  const EnsembleStudy study = EnsembleStudy::parse(text, path);
  const std::vector<long> runs = every_run(study);
  std::vector<EnsembleRow> rows;
  bool interrupted = false;
  {
    py::gil_scoped_release free_python;
    rows = run_ensemble(study, runs, threads, {}, [&] {
      py::gil_scoped_acquire python;  // between runs: Ctrl-C stops the study
      if (PyErr_CheckSignals() != 0) {
        PyErr_Clear();
        interrupted = true;
      }
      return interrupted;
    });
  }
  if (interrupted) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  py::dict columns;
  const auto& names = study.columns();
  const auto R = static_cast<py::ssize_t>(rows.size());
  for (size_t c = 0; c < names.size(); ++c) {
    py::array_t<double> a(R);
    auto v = a.mutable_unchecked<1>();
    for (py::ssize_t r = 0; r < R; ++r) {
      const EnsembleRow& row = rows[static_cast<size_t>(r)];
      v(r) = c == 0 ? static_cast<double>(row.run) : row.values[c - 1];
    }
    columns[names[c].c_str()] = a;
  }
  py::list summary;
  for (const ColumnSummary& s : summarize(names, rows)) {
    py::dict d;
    d["column"] = s.column;
    d["count"] = s.count;
    for (const SummaryStatistic& x : kSummaryStatistics) d[x.name] = s.*x.value;
    d["histogram"] = s.histogram;
    summary.append(d);
  }
  py::dict out;
  out["columns"] = columns;
  out["summary"] = summary;
  return out;
}

}  // namespace

void bind_ensemble(py::module_& m) {
  m.def("_ensemble", &run_study, py::arg("text"), py::arg("path"), py::arg("threads") = 0);
}

}  // namespace tumble::python
