// The engine's own blocks (sub-nets and their ports) as nodelets: registered by the engine, which
// knows no nodelets, and exported here by the nodelet layer.
#include "imagenets/blocks/sub_net_block.h"
#include "imagenets/blocks/sub_net_port.h"
#include "imagenets/register_block.h"

IMAGENETS_EXPORT_BLOCK_NODELET(imagenets::SubNetBlock)
IMAGENETS_EXPORT_BLOCK_NODELET(imagenets::SubNetInput)
IMAGENETS_EXPORT_BLOCK_NODELET(imagenets::SubNetOutput)
