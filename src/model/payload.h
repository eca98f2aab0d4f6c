/* vtdyn — Payloads and mass properties on a builder (model/payload.c): vt_default_payload_def,
 * vt_builder_add_payload and vt_builder_set_mass, declared in vtdyn.h. */
#ifndef VT_MODEL_PAYLOAD_H
#define VT_MODEL_PAYLOAD_H

#include "vtdyn.h"

#endif
