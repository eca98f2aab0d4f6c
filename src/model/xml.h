/* vtdyn — An XML document read safely (model/xml.c): with this library's libxml2 settings only,
 * whatever the host set, no entity, nothing outside the input, nothing printed, the input
 * bounded by VT_URDF_MAX_BYTES. */
#ifndef VT_MODEL_XML_H
#define VT_MODEL_XML_H

#include <stddef.h>

#include <libxml/tree.h>

#include "vtdyn.h"

/* what reads the parsed document (the URDF loader's from_doc): called by vt_xml_read with the
 * document while its error handling is in force; msg as vt_xml_read's */
typedef vt_status (*vt_xml_reader)(xmlDocPtr doc, void *user, char *msg);

/* Parses size bytes of XML (at most VT_URDF_MAX_BYTES; url names them in the messages) and hands
 * the document to read, then frees it. Statuses: read's; VT_ERR_XML (malformed, an entity, empty,
 * too large), VT_ERR_NO_MEMORY (libxml2's allocations); msg (VT_MESSAGE_SIZE, may be NULL) says
 * why. */
vt_status vt_xml_read(const char *xml, size_t size, const char *url, vt_xml_reader read, void *user, char *msg);

/* The line of an element of the document vt_xml_read hands over, past line 65535 too (where
 * libxml2 2.9's xmlGetLineNo says 65535 for an element); other nodes: xmlGetLineNo's. */
long vt_xml_line(const xmlNode *node);

/* A file's bytes into *text (malloc'ed, size bytes, the caller frees it; NULL on failure), at
 * most VT_URDF_MAX_BYTES read. Statuses: VT_ERR_FILE (cannot be opened or read, too large),
 * VT_ERR_NO_MEMORY. */
vt_status vt_xml_read_file(char **text, size_t *size, const char *path, char *msg);

#endif
