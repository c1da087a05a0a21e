# Sources of the standard block library.
set(MECHFLOW_LIBRARY_SOURCES
  blocks/library/discontinuities.cc
  blocks/library/first_order_lag.cc
  blocks/library/friction_from_normal_force.cc
  blocks/library/integrator.cc
  blocks/library/math_blocks.cc
  blocks/library/register_standard_blocks.cc
  blocks/library/sinks.cc
  blocks/library/sources.cc
)
