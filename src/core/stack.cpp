// Stack validation: owned by the readers work (see include/contour4d/core/stack.h).
#include "contour4d/core/stack.h"
