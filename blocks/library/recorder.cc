#include "blocks/library/recorder.h"

#include "blocks/library/port_names.h"

namespace mechflow::blocks {

RecorderBlock::RecorderBlock(const std::string& name, int num_inputs, int width) : Block("recorder", name) {
  for (int i = 0; i < num_inputs; ++i) DeclareInputPort(NumberedInputName(i, num_inputs), width);
}

}  // namespace mechflow::blocks
