#pragma once
/// \file grain.hpp
/// The umbrella header: everything a grain program needs.
///
/// grain is a header-only C++20 library for thermo-mechanical discrete element simulations of 2D
/// disks and 3D spheres. Models are types, coefficients are values:
///
/// \code
/// using Contact = grain::Interaction<grain::normal::Hertz<>, grain::tangent::SpringDashpotSlider,
///                                    grain::rolling::None, grain::conduction::BatchelorOBrien>;
/// grain::Simulation<grain::Sphere, grain::search::CellList, Contact> sim;
/// \endcode

#include <grain/version.hpp>

#include <grain/conditions/conditions.hpp>
#include <grain/conditions/regions.hpp>
#include <grain/contact/geometry.hpp>
#include <grain/core/error.hpp>
#include <grain/core/periodic_stage.hpp>
#include <grain/core/sums.hpp>
#include <grain/core/table.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>
#include <grain/integrate/integrators.hpp>
#include <grain/interaction.hpp>
#include <grain/io/io.hpp>
#include <grain/models/area/lu_morris_li_benyahia.hpp>
#include <grain/models/area/morris_pannala_ma_hrenya.hpp>
#include <grain/models/area/none.hpp>
#include <grain/models/area/zhou_yu_zulli.hpp>
#include <grain/models/concepts.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>
#include <grain/models/conduction/collisional.hpp>
#include <grain/models/conduction/combined.hpp>
#include <grain/models/conduction/none.hpp>
#include <grain/models/conduction/surrounding_layer.hpp>
#include <grain/models/conduction/thermal_pipe.hpp>
#include <grain/models/conduction/voronoi_a.hpp>
#include <grain/models/conduction/voronoi_b.hpp>
#include <grain/models/convection/none.hpp>
#include <grain/models/convection/ranz_marshall.hpp>
#include <grain/models/convection/whitaker.hpp>
#include <grain/models/normal/capillary.hpp>
#include <grain/models/normal/dmt.hpp>
#include <grain/models/normal/hertz.hpp>
#include <grain/models/normal/hertz_damping.hpp>
#include <grain/models/normal/hertz_equivalent.hpp>
#include <grain/models/normal/jkr.hpp>
#include <grain/models/normal/linear_spring_dashpot.hpp>
#include <grain/models/normal/walton_braun.hpp>
#include <grain/models/radiation/none.hpp>
#include <grain/models/radiation/zhou_yu_zulli.hpp>
#include <grain/models/rolling/constant.hpp>
#include <grain/models/rolling/epsd.hpp>
#include <grain/models/rolling/none.hpp>
#include <grain/models/rolling/viscous.hpp>
#include <grain/models/tangent/dashpot.hpp>
#include <grain/models/tangent/dashpot_slider.hpp>
#include <grain/models/tangent/di_renzo_di_maio.hpp>
#include <grain/models/tangent/langston_tuzun_heyes.hpp>
#include <grain/models/tangent/mindlin.hpp>
#include <grain/models/tangent/none.hpp>
#include <grain/models/tangent/slider.hpp>
#include <grain/models/tangent/spring.hpp>
#include <grain/models/tangent/spring_dashpot_slider.hpp>
#include <grain/models/tangent/spring_slider.hpp>
#include <grain/models/tangent/tsuji.hpp>
#include <grain/models/tangent/zheng_zhu_yu.hpp>
#include <grain/particles/material.hpp>
#include <grain/particles/shape.hpp>
#include <grain/particles/storage.hpp>
#include <grain/presets.hpp>
#include <grain/search/search.hpp>
#include <grain/setup/generate.hpp>
#include <grain/setup/insertion.hpp>
#include <grain/simulation.hpp>
#include <grain/walls/facets.hpp>
#include <grain/walls/obstacle.hpp>
#include <grain/walls/walls.hpp>
