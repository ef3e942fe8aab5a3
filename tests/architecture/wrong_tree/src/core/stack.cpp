// A deliberately wrong include: core may not include motion, a layer above it.
#include "contour4d/motion/morph.h"
