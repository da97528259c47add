#include "sibling.h"
int deep;
