# Sources of the standard block library: one file per block, plus the bases
# shared by step/ramp (switch_at_time) and abs/saturation/dead_zone
# (piecewise_linear), and the registration of every type.
set(MECHFLOW_LIBRARY_SOURCES
  blocks/library/abs.cc
  blocks/library/clock.cc
  blocks/library/constant.cc
  blocks/library/dead_zone.cc
  blocks/library/first_order_lag.cc
  blocks/library/friction_from_normal_force.cc
  blocks/library/gain.cc
  blocks/library/held_input.cc
  blocks/library/integrator.cc
  blocks/library/interpolation.cc
  blocks/library/lookup.cc
  blocks/library/mechanism_block.cc
  blocks/library/mechanism_sparsity.cc
  blocks/library/motion.cc
  blocks/library/piecewise_linear.cc
  blocks/library/product.cc
  blocks/library/ramp.cc
  blocks/library/recorder.cc
  blocks/library/register_standard_blocks.cc
  blocks/library/sample_hold.cc
  blocks/library/saturation.cc
  blocks/library/sine.cc
  blocks/library/step.cc
  blocks/library/sum.cc
  blocks/library/switch_at_time.cc
  blocks/library/table.cc
)
