// Fuzz target of the reading of ParaView series files (.vtk.series) by grain::io::vtk:
// grain::io::detail::read_series, and the resume of a VtkWriter (VtkOptions::resume), which
// reads the series of an earlier run, keeps its entries before the current time, removes the
// files of the later ones and numbers on. Any series file is either taken up or rejected with
// grain::InputError; nothing outside the writer's folder is touched.
//
// The input is the particle series; the wall series is a copy of it.

#include "fuzz_support.hpp"

#include <grain/grain.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace {

using Sim = grain::Simulation<grain::Disk, grain::search::CellList, grain::presets::LinearCoulomb>;

Sim& simulation() {
  static Sim sim = [] {
    Sim s;
    grain::Material m;
    m.density = 2500;
    m.young = 1e7;
    const auto k = s.add_material(m);
    s.add_particle({.position = {0.0, 0.0}, .radius = 0.01, .material = k});
    s.initialize();
    s.steps(3);
    return s;
  }();
  return sim;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto dir = grain_fuzz::scratch() / "vtk";
  std::filesystem::create_directories(dir);
  const std::string prefix = (dir / "fz").string();
  grain_fuzz::write_input("vtk/fz_particles.vtk.series", data, size);
  grain_fuzz::write_input("vtk/fz_walls.vtk.series", data, size);
  std::error_code ignored;
  std::filesystem::remove(dir / "fz_contacts.vtk.series", ignored);
  try {
    const auto files = grain::io::detail::read_series(prefix, "particles");
    for (const auto& [name, time] : files)
      if (!std::isfinite(time) && !std::isnan(time) && !std::isinf(time))
        grain_fuzz::fail("impossible time");
    auto writer = grain::io::vtk(prefix, {.resume = true});
    writer.start(simulation());
    if (writer.count < 0) grain_fuzz::fail("negative frame number after resume");
    if (writer.particle_files.size() > files.size()) grain_fuzz::fail("entries made up");
  } catch (const grain::InputError&) {
  }
  return 0;
}
