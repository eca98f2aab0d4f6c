/* An XML document read by libxml2 with this library's settings only, for the URDF loader.
 *
 * The parse depends on none of libxml2's process-wide defaults (configure() sets every field they
 * would set) and changes none; URDF needs no entity, so a document that declares or refers to one
 * is refused as soon as it does (no expansion, no external file, DTD or entity loader; XInclude is
 * never processed). libxml2's errors come through a structured handler on the parser context, and
 * those it reports with no context (allocations) through the calling thread's structured handler,
 * which is this file's while vt_xml_read runs and the caller's again before it returns: nothing is
 * printed. Inputs are bounded (VT_URDF_MAX_BYTES), checked before they are read whole.
 */
#define _POSIX_C_SOURCE 200809L /* fileno */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include <libxml/entities.h>
#include <libxml/globals.h> /* xmlStructuredError: the calling thread's */
#include <libxml/parser.h>
#include <libxml/parserInternals.h> /* xmlCreateMemoryParserCtxt */
#include <libxml/SAX2.h>
#include <libxml/xmlerror.h>

#include "model/xml.h"
#include "base/status.h"

/* What a parse met: libxml2's first error, kept by the structured handler of its parser
 * context, and the first entity declaration or reference, refused by this loader's SAX
 * callbacks (URDF needs no entity: refusing them keeps expansion, external files and the
 * host's entity loader out of the parse). */
typedef struct {
    int set;            /* an error or warning that fails the parse was met */
    int code;           /* its xmlParserErrors code (XML_ERR_NO_MEMORY: out of memory) */
    int line;
    char text[192];
    int entity;         /* an entity was declared or referred to: the parse was stopped */
    int entity_line;
    char entity_name[72];
} xml_error;

static xml_error *parse_state(void *ctx)
{
    xmlParserCtxtPtr ctxt = (xmlParserCtxtPtr)ctx;
    return ctxt ? (xml_error *)ctxt->_private : NULL;
}

/* the first entity met: kept with its line, and the parse stopped there (nothing loaded) */
static void refuse_entity(void *ctx, const char *kind, const xmlChar *name, const char *after)
{
    xmlParserCtxtPtr ctxt = (xmlParserCtxtPtr)ctx;
    xml_error *x = parse_state(ctx);
    if (!x) return;
    if (!x->entity) {
        x->entity = 1;
        x->entity_line = ctxt->input ? ctxt->input->line : 0;
        snprintf(x->entity_name, sizeof x->entity_name, "%s%.48s%s", kind, name ? (const char *)name : "", after);
    }
    xmlStopParser(ctxt);
}

static void on_entity_decl(void *ctx, const xmlChar *name, int type, const xmlChar *public_id,
                           const xmlChar *system_id, xmlChar *content)
{
    (void)public_id;
    (void)system_id;
    (void)content;
    const int parameter = type == XML_INTERNAL_PARAMETER_ENTITY || type == XML_EXTERNAL_PARAMETER_ENTITY;
    refuse_entity(ctx, parameter ? "<!ENTITY % " : "<!ENTITY ", name, ">");
}

static void on_unparsed_entity_decl(void *ctx, const xmlChar *name, const xmlChar *public_id,
                                    const xmlChar *system_id, const xmlChar *notation)
{
    (void)public_id;
    (void)system_id;
    (void)notation;
    refuse_entity(ctx, "<!ENTITY ", name, ">");
}

static void on_reference(void *ctx, const xmlChar *name)
{
    refuse_entity(ctx, "&", name, ";");
}

/* no entity but the five predefined ones (&lt; &gt; &amp; &apos; &quot;) */
static xmlEntityPtr on_get_entity(void *ctx, const xmlChar *name)
{
    (void)ctx;
    return xmlGetPredefinedEntity(name);
}

static xmlEntityPtr on_get_parameter_entity(void *ctx, const xmlChar *name)
{
    (void)ctx;
    (void)name;
    return NULL;
}

/* nothing loaded from outside the input: no external subset, no external entity, whatever
 * the host set (xmlLoadExtDtdDefaultValue, xmlSetExternalEntityLoader) */
static void on_external_subset(void *ctx, const xmlChar *name, const xmlChar *external_id, const xmlChar *system_id)
{
    (void)ctx;
    (void)name;
    (void)external_id;
    (void)system_id;
}

static xmlParserInputPtr on_resolve_entity(void *ctx, const xmlChar *public_id, const xmlChar *system_id)
{
    (void)ctx;
    (void)public_id;
    (void)system_id;
    return NULL;
}

static void keep_error(xml_error *x, const xmlError *e)
{
    if (!x || !e) return;
    if (e->code == XML_WAR_UNDECLARED_ENTITY || e->code == XML_ERR_UNDECLARED_ENTITY) { /* a reference */
        if (!x->entity) {
            x->entity = 1;
            x->entity_line = e->line;
            snprintf(x->entity_name, sizeof x->entity_name, "&%.48s; (undeclared)", e->str1 ? e->str1 : "");
        }
        return;
    }
    /* the first error, but out of memory over any (the errors it causes come after it, or
     * before it when libxml2 reports the failed allocation late) */
    if ((x->set && !(e->code == XML_ERR_NO_MEMORY && x->code != XML_ERR_NO_MEMORY)) || e->level < XML_ERR_ERROR)
        return;
    x->set = 1;
    x->code = e->code;
    x->line = e->line;
    snprintf(x->text, sizeof x->text, "%s", e->message ? e->message : "error");
    size_t n = strlen(x->text);
    while (n > 0 && (x->text[n - 1] == '\n' || x->text[n - 1] == ' ')) x->text[--n] = '\0';
}

#if LIBXML_VERSION >= 21200
#define VT_XML_ERROR const xmlError
#else
#define VT_XML_ERROR xmlError
#endif

/* the parser context's structured handler: the context's errors */
static void on_xml_error(void *data, VT_XML_ERROR *e)
{
    (void)data; /* the parser context's userData: the context itself, but e->ctxt says so */
    keep_error(e ? parse_state(e->ctxt) : NULL, e);
}

/* the calling thread's structured handler while a URDF is read: what libxml2 2.9 reports with
 * no parser context (an allocation that fails while the context is made, in the tree's
 * functions, in the dictionary), which would otherwise go to the thread's generic handler,
 * which prints */
static void on_thread_error(void *data, VT_XML_ERROR *e)
{
    xml_error *x = data;
    if (e && e->ctxt && parse_state(e->ctxt) == x) return; /* the context's own: kept there */
    keep_error(x, e);
}

/* An element's line past 65535: libxml2 2.9 keeps an element's line in 16 bits (65535 beyond)
 * and XML_PARSE_BIG_LINES the full line of text nodes only, so the element created here gets
 * its line, as libxml2 takes it (the input's line when the start tag is read), in its psvi,
 * which nothing else uses without schema validation (vt_xml_line reads it). */
static void on_start_element(void *ctx, const xmlChar *localname, const xmlChar *prefix, const xmlChar *uri,
                             int nb_namespaces, const xmlChar **namespaces, int nb_attributes, int nb_defaulted,
                             const xmlChar **attributes)
{
    xmlParserCtxtPtr ctxt = (xmlParserCtxtPtr)ctx;
    const xmlNodePtr parent = ctxt->node;
    xmlSAX2StartElementNs(ctx, localname, prefix, uri, nb_namespaces, namespaces, nb_attributes, nb_defaulted,
                          attributes);
    xmlNodePtr node = ctxt->node; /* the new element, or the parent when it could not be made */
    if (node && node != parent && node->type == XML_ELEMENT_NODE && node->line == 65535 && ctxt->input &&
        ctxt->input->line >= 65535)
        node->psvi = (void *)(intptr_t)ctxt->input->line;
}

long vt_xml_line(const xmlNode *node)
{
    if (node->type == XML_ELEMENT_NODE && node->line == 65535 && node->psvi) return (long)(intptr_t)node->psvi;
    return xmlGetLineNo(node);
}

/* The parser context's settings, all of them this loader's, none the process's: libxml2 2.9's
 * xmlNewParserCtxt copies the host's defaults into the context (xmlSubstituteEntitiesDefault,
 * xmlLoadExtDtdDefaultValue, xmlDoValidityCheckingDefaultValue, xmlPedanticParserDefault,
 * xmlKeepBlanksDefault, xmlLineNumbersDefault, xmlGetWarningsDefaultValue, the default SAX
 * version): each is set here. Errors go to this context's structured handler only (no generic
 * or validity channel, which print), entities are refused, nothing outside the input is loaded,
 * no network (NONET), no XInclude (never processed). The tree is kept small, a robot of 100,000
 * links being some 30 MB of text: short texts and attribute values stored in their node
 * (COMPACT; the tree is never modified), and the white space between elements, which URDF does
 * not read, left out (NOBLANKS; the lines of the elements are their own, on_start_element). */
static void configure(xmlParserCtxtPtr ctxt, xml_error *err)
{
    xmlSAXVersion(ctxt->sax, 2); /* SAX2 callbacks, whatever xmlSAXDefaultVersion() said */
    xmlCtxtUseOptions(ctxt, XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_BIG_LINES |
                                XML_PARSE_COMPACT | XML_PARSE_NOBLANKS);
    ctxt->replaceEntities = 0;
    ctxt->loadsubset = 0;
    ctxt->validate = 0;
    ctxt->pedantic = 0;
    ctxt->keepBlanks = 0;
    ctxt->linenumbers = 1;
    ctxt->recovery = 0;
    ctxt->vctxt.error = NULL;
    ctxt->vctxt.warning = NULL;
    ctxt->_private = err;
    xmlSAXHandlerPtr sax = ctxt->sax;
    sax->ignorableWhitespace = xmlSAX2IgnorableWhitespace; /* blanks between elements: dropped */
    sax->startElementNs = on_start_element;
    sax->warning = NULL;
    sax->error = NULL;
    sax->fatalError = NULL;
    sax->serror = on_xml_error; /* this parse's errors only: no global handler */
    sax->entityDecl = on_entity_decl;
    sax->unparsedEntityDecl = on_unparsed_entity_decl;
    sax->reference = on_reference;
    sax->getEntity = on_get_entity;
    sax->getParameterEntity = on_get_parameter_entity;
    sax->externalSubset = on_external_subset;
    sax->resolveEntity = on_resolve_entity;
}

/* libxml2's first error as a status and message: out of memory over any other, then a refused
 * entity, then malformed XML */
static vt_status parse_outcome(const xml_error *err, const xmlDoc *doc, char *msg)
{
    if (err->set && err->code == XML_ERR_NO_MEMORY)
        return vt_fail(msg, VT_ERR_NO_MEMORY, "out of memory while parsing the XML (libxml2, line %d)", err->line);
    if (err->entity)
        return vt_fail(msg, VT_ERR_XML, "XML entities are refused (URDF needs none): %s on line %d", err->entity_name,
                       err->entity_line);
    if (err->set || !doc) return vt_fail(msg, VT_ERR_XML, "malformed XML on line %d: %s", err->line, err->text);
    return VT_OK;
}

vt_status vt_xml_read(const char *xml, size_t size, const char *url, vt_xml_reader read, void *user, char *msg)
{
    if (size > (size_t)VT_URDF_MAX_BYTES) /* the callers check first; libxml2 takes an int */
        return vt_fail(msg, VT_ERR_XML, "%.160s: larger than VT_URDF_MAX_BYTES (%d bytes)", url, VT_URDF_MAX_BYTES);
    if (size == 0) return vt_fail(msg, VT_ERR_XML, "malformed XML on line 1: the document is empty");
    xml_error err;
    memset(&err, 0, sizeof err);
    /* the calling thread's handler is ours until the caller's is put back below (libxml2 keeps
     * it per thread: no other thread sees it; the process's defaults are not touched) */
    const xmlStructuredErrorFunc host_handler = xmlStructuredError;
    void *const host_context = xmlStructuredErrorContext;
    xmlSetStructuredErrorFunc(&err, on_thread_error);
    xmlInitParser(); /* once per process, as libxml2 asks; idempotent */
    xmlParserCtxtPtr ctxt = xmlCreateMemoryParserCtxt(xml, (int)size);
    if (!ctxt || !ctxt->sax) {
        xmlFreeParserCtxt(ctxt);
        xmlSetStructuredErrorFunc(host_context, host_handler);
        return vt_fail(msg, VT_ERR_NO_MEMORY, "out of memory (libxml2 parser)");
    }
    configure(ctxt, &err);
    xmlParseDocument(ctxt);
    xmlDocPtr doc = ctxt->myDoc;
    ctxt->myDoc = NULL;
    if (!err.set && !err.entity && (!doc || !ctxt->wellFormed)) { /* an error only in the context's lastError */
        const xmlError *e = xmlCtxtGetLastError(ctxt);
        err.set = 1;
        err.code = e ? e->code : (int)ctxt->errNo;
        err.line = e ? e->line : 0;
        snprintf(err.text, sizeof err.text, "%s", e && e->message ? e->message : "not well-formed");
        size_t n = strlen(err.text);
        while (n > 0 && (err.text[n - 1] == '\n' || err.text[n - 1] == ' ')) err.text[--n] = '\0';
    }
    if (ctxt->errNo == XML_ERR_NO_MEMORY) { /* xmlErrMemory's mark, whatever was reported */
        err.set = 1;
        err.code = XML_ERR_NO_MEMORY;
    }
    vt_status st = parse_outcome(&err, doc, msg);
    if (!st) st = read(doc, user, msg); /* still under this file's thread handler */
    xmlFreeDoc(doc);
    xmlFreeParserCtxt(ctxt);
    xmlSetStructuredErrorFunc(host_context, host_handler);
    return st;
}

vt_status vt_xml_read_file(char **text, size_t *size, const char *path, char *msg)
{
    *text = NULL;
    *size = 0;
    /* read here, not by libxml2: a file that cannot be read is told from malformed XML; at most
     * VT_URDF_MAX_BYTES + 1 bytes are read (a regular file's size is checked before any), so
     * /dev/zero or an endless pipe is refused at the bound, not when memory runs out */
    errno = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        const int e = errno;
        return vt_fail(msg, VT_ERR_FILE, "cannot open \"%.180s\": %s", path,
                       e == ENOENT ? "no such file" : e == EACCES ? "permission denied" : "error");
    }
    const size_t limit = (size_t)VT_URDF_MAX_BYTES;
    struct stat sb;
    vt_status st = VT_OK;
    if (fstat(fileno(f), &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size > (off_t)limit)
        st = vt_fail(msg, VT_ERR_FILE, "\"%.150s\" is larger than VT_URDF_MAX_BYTES (%d bytes)", path, VT_URDF_MAX_BYTES);
    char *buf = NULL;
    size_t n = 0, cap = 0;
    while (!st) {
        if (n == cap) {
            if (cap > limit) { /* limit + 1 bytes read: too large */
                st = vt_fail(msg, VT_ERR_FILE, "\"%.150s\" is larger than VT_URDF_MAX_BYTES (%d bytes)", path,
                             VT_URDF_MAX_BYTES);
                break;
            }
            size_t nc = cap ? 2 * cap : 65536;
            if (nc > limit + 1) nc = limit + 1;
            char *p = realloc(buf, nc + 1);
            if (!p) {
                st = vt_fail(msg, VT_ERR_NO_MEMORY, "out of memory reading \"%.180s\"", path);
                break;
            }
            buf = p;
            cap = nc;
        }
        const size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) {
            if (ferror(f)) st = vt_fail(msg, VT_ERR_FILE, "cannot read \"%.180s\" (a directory?)", path);
            break;
        }
    }
    fclose(f);
    if (st) {
        free(buf);
        return st;
    }
    *text = buf;
    *size = n;
    return VT_OK;
}
