#include "colours-missing.inc"
