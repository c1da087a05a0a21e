# Sources of the standard block library (one file per block).
set(MECHFLOW_LIBRARY_SOURCES
  blocks/library/register_standard_blocks.cc
)
