// The firmware includes "cdc_device.h" by its bare name (its build lists class/cdc as a folder).
#include "class/cdc/cdc_device.h"
