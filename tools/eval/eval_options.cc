#include "tools/eval/eval_options.h"
