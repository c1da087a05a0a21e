#include "blocks/block_factory.h"

namespace mechflow::blocks {

void RegisterStandardBlocks(BlockRegistry*) {}

}  // namespace mechflow::blocks
