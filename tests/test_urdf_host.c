/* src/model/urdf.c in a host program that changed libxml2's process-wide defaults, as programs
 * that parse other XML do: entity substitution, loading external DTDs with default attributes,
 * validation, no blanks, pedantic warnings, SAX1. The loader must not depend on them nor change
 * them: a URDF gives the same model as before the host set them (compared number for number
 * with loads done in main() before) and as the C scene; a document naming a local file through
 * an external entity, a parameter entity or an external DTD is refused without the file being
 * opened (inotify watches it; its unique marker is in no name nor message); nothing is written
 * to standard error (fd 2 redirected to a file around each call); and the host's settings, its
 * error handlers and its external entity loader (which must never be called) are as they were
 * after every call. An own executable: the settings are the process's. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, dup, fileno */
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/inotify.h>
#endif

#include <libxml/globals.h>
#include <libxml/parser.h>
#include <libxml/xmlIO.h>

#include "vt_test.h"

#ifndef VT_TEST_URDF_DIR
#error "VT_TEST_URDF_DIR: the directory of the test's URDF files (tests/meson.build)"
#endif

/* ---- the host's libxml2 settings ----------------------------------------------------------- */

typedef struct {
    int substitute, load_ext_dtd, keep_blanks, pedantic, warnings, validity, line_numbers, indent;
    xmlGenericErrorFunc generic;
    void *generic_ctx;
    xmlStructuredErrorFunc structured;
    void *structured_ctx;
    xmlExternalEntityLoader loader;
    startElementSAXFunc sax_start; /* xmlDefaultSAXHandler's, changed by xmlSAXDefaultVersion */
} host_settings;

static host_settings read_settings(void)
{
    host_settings h;
    memset(&h, 0, sizeof h);
    h.substitute = xmlSubstituteEntitiesDefaultValue;
    h.load_ext_dtd = xmlLoadExtDtdDefaultValue;
    h.keep_blanks = xmlKeepBlanksDefaultValue;
    h.pedantic = xmlPedanticParserDefaultValue;
    h.warnings = xmlGetWarningsDefaultValue;
    h.validity = xmlDoValidityCheckingDefaultValue;
    h.line_numbers = xmlLineNumbersDefaultValue;
    h.indent = xmlIndentTreeOutput;
    h.generic = xmlGenericError;
    h.generic_ctx = xmlGenericErrorContext;
    h.structured = xmlStructuredError;
    h.structured_ctx = xmlStructuredErrorContext;
    h.loader = xmlGetExternalEntityLoader();
    h.sax_start = xmlDefaultSAXHandler.startElement;
    return h;
}

static void same_settings(const host_settings *a, const host_settings *b)
{
    assert_int_equal(a->substitute, b->substitute);
    assert_int_equal(a->load_ext_dtd, b->load_ext_dtd);
    assert_int_equal(a->keep_blanks, b->keep_blanks);
    assert_int_equal(a->pedantic, b->pedantic);
    assert_int_equal(a->warnings, b->warnings);
    assert_int_equal(a->validity, b->validity);
    assert_int_equal(a->line_numbers, b->line_numbers);
    assert_int_equal(a->indent, b->indent);
    assert_true(a->generic == b->generic && a->generic_ctx == b->generic_ctx);
    assert_true(a->structured == b->structured && a->structured_ctx == b->structured_ctx);
    assert_true(a->loader == b->loader);
    assert_true(a->sax_start == b->sax_start);
}

/* every default a host may change, set against the loader's needs */
static void set_host_defaults(void)
{
    xmlSubstituteEntitiesDefault(1);
    xmlLoadExtDtdDefaultValue = XML_DETECT_IDS | XML_COMPLETE_ATTRS;
    xmlKeepBlanksDefault(0);
    xmlPedanticParserDefault(1);
    xmlGetWarningsDefaultValue = 1;
    xmlDoValidityCheckingDefaultValue = 1;
    xmlLineNumbersDefault(0);
#ifdef LIBXML_SAX1_ENABLED
    xmlSAXDefaultVersion(1);
#endif
}

/* ---- loads with standard error watched ----------------------------------------------------- */

typedef struct {
    vt_status status;
    char msg[256];
    vt_builder *builder;
} load_result;

/* a load (path, or else xml) with fd 2 sent to a temporary file: nothing may be written there,
 * and the host's settings must be as they were */
static load_result load_quietly(const char *path, const char *xml, const vt_urdf_options *opt)
{
    load_result r;
    memset(&r, 0, sizeof r);
    const host_settings before = read_settings();
    fflush(stderr);
    FILE *cap = tmpfile();
    assert_non_null(cap);
    const int saved = dup(2);
    assert_true(saved >= 0);
    assert_true(dup2(fileno(cap), 2) >= 0);
    r.status = path ? vt_urdf_builder(&r.builder, path, opt, r.msg) : vt_urdf_builder_string(&r.builder, xml, opt, r.msg);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    char said[512] = "";
    rewind(cap);
    const size_t n = fread(said, 1, sizeof said - 1, cap);
    said[n] = '\0';
    fclose(cap);
    if (n) fail_msg("printed on standard error: \"%s\"", said);
    const host_settings after = read_settings();
    same_settings(&before, &after);
    return r;
}

/* ---- the normal robot ---------------------------------------------------------------------- */

/* the instant outputs compared (motion given at one state) */
enum { NOUT = 64 };
typedef struct {
    int nbody, nq, nv, nframe;
    double out[NOUT];
} fingerprint;

static fingerprint reference_plain; /* the double link loaded before the host's settings */
static fingerprint reference_string;

static const char *robot_string =
    "<?xml version=\"1.0\"?>\n"
    "<!-- a comment, white space and a predefined entity: all kept whatever the host set -->\n"
    "<robot name=\"r\">\n"
    "  <link name=\"world\"/>\n"
    "  <link name=\"arm&amp;tool\">\n"
    "    <inertial><origin xyz=\"0.5 0 0\"/><mass value=\"2\"/>\n"
    "      <inertia ixx=\"0.01\" iyy=\"0.2\" izz=\"0.2\"/></inertial>\n"
    "  </link>\n"
    "  <joint name=\"hinge\" type=\"revolute\">\n"
    "    <parent link=\"world\"/><child link=\"arm&amp;tool\"/><axis xyz=\"0 1 0\"/>\n"
    "  </joint>\n"
    "</robot>\n";

/* a model's fingerprint: its sizes and the instant at one state (no cmocka: used in main too) */
static int fingerprint_of(vt_builder *b, fingerprint *f)
{
    memset(f, 0, sizeof *f);
    vt_model *m = NULL;
    vt_data *d = NULL;
    if (vt_builder_build(&m, b) != VT_OK || vt_data_create(&d, m) != VT_OK) {
        vt_model_free(m);
        return 1;
    }
    f->nbody = m->nbody;
    f->nq = m->nq;
    f->nv = m->nv;
    f->nframe = m->nframe;
    for (int k = 0; k < m->nv; k++) {
        d->q[k] = 0.3 - 0.7 * k;
        d->qd[k] = -1.1 + 0.4 * k;
        d->qdd[k] = 0.9 + 0.2 * k;
    }
    int bad = vt_inverse_dynamics_motion(m, d) != VT_OK;
    int n = 0;
    for (int k = 0; k < m->nv && n < NOUT; k++) f->out[n++] = d->qfrc_drive[k];
    for (int k = 0; k < 3 * (m->nbody + 1) && n < NOUT; k++) f->out[n++] = d->jnt_force[k];
    for (int k = 0; k < 3 * (m->nbody + 1) && n < NOUT; k++) f->out[n++] = d->jnt_moment[k];
    vt_data_free(d);
    vt_model_free(m);
    return bad;
}

static vt_urdf_options double_link_options(void)
{
    vt_urdf_options opt = vt_default_urdf_options();
    opt.model.gravity[1] = -9.81; /* the paper's */
    opt.model.gravity[2] = 0.0;
    return opt;
}

/* (a) the same model as before the host's settings, number for number, and as the C scene */
static void test_normal_robot(void **state)
{
    (void)state;
    const vt_urdf_options opt = double_link_options();
    load_result r = load_quietly(VT_TEST_URDF_DIR "/double_link.urdf", NULL, &opt);
    if (r.status != VT_OK) fail_msg("double_link.urdf: %s (%s)", vt_status_string(r.status), r.msg);
    fingerprint f;
    assert_int_equal(fingerprint_of(r.builder, &f), 0);
    vt_builder_free(r.builder);
    assert_memory_equal(&f, &reference_plain, sizeof f);
    /* and the paper's double link written in C (examples/scenes.c) */
    vt_model *mc;
    assert_ok(vt_scene_double_link(&mc, 0));
    vt_data *dc;
    assert_ok(vt_data_create(&dc, mc));
    for (int k = 0; k < 2; k++) {
        dc->q[k] = 0.3 - 0.7 * k;
        dc->qd[k] = -1.1 + 0.4 * k;
        dc->qdd[k] = 0.9 + 0.2 * k;
    }
    assert_ok(vt_inverse_dynamics_motion(mc, dc));
    assert_int_equal(f.nbody, 2);
    for (int k = 0; k < 2; k++) assert_near(f.out[k], dc->qfrc_drive[k], 1e-12 * fabs(dc->qfrc_drive[k]) + 1e-9);
    vt_data_free(dc);
    vt_model_free(mc);

    /* white space, a comment and &amp;: the same as before, the name with its '&' */
    r = load_quietly(NULL, robot_string, NULL);
    if (r.status != VT_OK) fail_msg("string: %s (%s)", vt_status_string(r.status), r.msg);
    assert_int_equal(vt_builder_find_body(r.builder, "arm&tool"), 1);
    assert_int_equal(fingerprint_of(r.builder, &f), 0);
    vt_builder_free(r.builder);
    assert_memory_equal(&f, &reference_string, sizeof f);

    /* a malformed file still names its line (line numbers whatever xmlLineNumbersDefault) */
    r = load_quietly(NULL, "<robot name=\"r\">\n<link name=\"a\">\n</robot>", NULL);
    assert_int_equal(r.status, VT_ERR_XML);
    assert_non_null(strstr(r.msg, "line 3"));
    r = load_quietly(NULL, "<robot name=\"r\">\n\n<link/></robot>", NULL);
    assert_int_equal(r.status, VT_ERR_BAD_NAME);
    assert_non_null(strstr(r.msg, "line 3"));
}

/* ---- documents that name local files -------------------------------------------------------- */

static char dir[256], secret[300], decls[300], dtd[300], marker[64];
static int host_loader_calls;

static xmlParserInputPtr counting_loader(const char *url, const char *id, xmlParserCtxtPtr ctxt)
{
    (void)url;
    (void)id;
    (void)ctxt;
    host_loader_calls++;
    return NULL;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* The files an attacker's URDF names: their content holds the marker; an inotify watch sees any
 * open of them (Linux). */
static int setup_files(void **state)
{
    (void)state;
    snprintf(dir, sizeof dir, "%s/vtdyn_urdf_host_XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(dir)) return 1;
    snprintf(marker, sizeof marker, "MARKER%ldX%ld", (long)getpid(), (long)time(NULL));
    snprintf(secret, sizeof secret, "%s/secret.txt", dir);
    snprintf(decls, sizeof decls, "%s/decls.ent", dir);
    snprintf(dtd, sizeof dtd, "%s/robot.dtd", dir);
    char text[256];
    write_file(secret, marker);
    snprintf(text, sizeof text, "<!ENTITY n \"%s\">", marker);
    write_file(decls, text);
    snprintf(text, sizeof text, "<!ENTITY n \"%s\">\n<!ATTLIST link name CDATA \"%s\">", marker, marker);
    write_file(dtd, text);
    return 0;
}

static int teardown_files(void **state)
{
    (void)state;
    remove(secret);
    remove(decls);
    remove(dtd);
    rmdir(dir);
    return 0;
}

/* (b), (c): each document refused (or, for the external DTD, loaded without it), none of the
 * files opened nor their marker anywhere */
static void test_local_files(void **state)
{
    (void)state;
#ifdef __linux__
    const int watch = inotify_init1(IN_NONBLOCK);
    assert_true(watch >= 0);
    assert_true(inotify_add_watch(watch, dir, IN_OPEN | IN_ACCESS) >= 0);
#endif
    char xml[8][1024];
    /* an external general entity in an attribute, then in content */
    snprintf(xml[0], sizeof xml[0],
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM \"file://%s\">]>\n"
             "<robot name=\"r\"><link name=\"world\"/><link name=\"&x;\"/></robot>", secret);
    snprintf(xml[1], sizeof xml[1],
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM \"file://%s\">]>\n"
             "<robot name=\"r\"><link name=\"world\"/><link name=\"a\">&x;</link></robot>", secret);
    /* the same by a relative name and a plain path */
    snprintf(xml[2], sizeof xml[2],
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM \"%s\">]>\n"
             "<robot name=\"r\"><link name=\"world\"/><link name=\"a\">&x;</link></robot>", secret);
    /* a parameter entity whose file declares the entity used as a link's name */
    snprintf(xml[3], sizeof xml[3],
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY %% p SYSTEM \"file://%s\"> %%p; ]>\n"
             "<robot name=\"r\"><link name=\"world\"/><link name=\"&n;\"/></robot>", decls);
    /* an internal entity referring to the external one, in an attribute */
    snprintf(xml[4], sizeof xml[4],
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM \"file://%s\"><!ENTITY y \"&x;\">]>\n"
             "<robot name=\"r\"><link name=\"world\"/><link name=\"&y;\"/></robot>", secret);
    /* an external DTD declaring the entity used */
    snprintf(xml[5], sizeof xml[5],
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot SYSTEM \"file://%s\">\n"
             "<robot name=\"r\"><link name=\"world\"/><link name=\"&n;\"/></robot>", dtd);
    const int nrefused = 6;
    /* an external DTD whose default attribute would name an unnamed link */
    snprintf(xml[6], sizeof xml[6],
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot SYSTEM \"file://%s\">\n"
             "<robot name=\"r\"><link name=\"world\"/><link/></robot>", dtd);
    /* XInclude of the file: never processed, the element is not URDF and is ignored */
    snprintf(xml[7], sizeof xml[7],
             "<?xml version=\"1.0\"?>\n<robot name=\"r\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">"
             "<link name=\"world\"/><link name=\"a\"/><xi:include href=\"file://%s\" parse=\"text\"/>"
             "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/><child link=\"a\"/></joint></robot>", secret);
    vt_urdf_options opt = vt_default_urdf_options();
    opt.floating = 1; /* every root a body named after its link */
    for (int k = 0; k < 8; k++) {
        load_result r = load_quietly(NULL, xml[k], &opt);
        if (k < nrefused) {
            if (r.status != VT_ERR_XML || !strstr(r.msg, "entit") || r.builder)
                fail_msg("document %d: status %d, message \"%s\": not refused for its entity", k, (int)r.status, r.msg);
        } else if (k == 6) {
            if (r.status != VT_ERR_BAD_NAME || !strstr(r.msg, "needs a name"))
                fail_msg("document %d: status %d, message \"%s\": the DTD's default name was taken", k, (int)r.status,
                         r.msg);
        } else {
            if (r.status != VT_OK) fail_msg("document %d: status %d, message \"%s\"", k, (int)r.status, r.msg);
            assert_int_equal(vt_builder_find_body(r.builder, "a"), 1);
        }
        if (strstr(r.msg, marker)) fail_msg("document %d: the file's content in the message \"%s\"", k, r.msg);
        if (r.builder) assert_true(vt_builder_find_body(r.builder, marker) < 0);
        vt_builder_free(r.builder);
        /* the same from a file: the loader reads only the path it is given */
        char path[400];
        snprintf(path, sizeof path, "%s/doc%d.urdf", dir, k);
        write_file(path, xml[k]);
#ifdef __linux__
        char events[4096];
        while (read(watch, events, sizeof events) > 0) continue; /* the writes' own events */
#endif
        const load_result rf = load_quietly(path, NULL, &opt);
        remove(path);
        assert_int_equal(rf.status, r.status);
        if (strstr(rf.msg, marker)) fail_msg("document %d: the file's content in the message \"%s\"", k, rf.msg);
        vt_builder_free(rf.builder);
#ifdef __linux__
        /* no open of the secret files: only the document itself was opened */
        ssize_t n;
        while ((n = read(watch, events, sizeof events)) > 0)
            for (char *p = events; p < events + n;) {
                const struct inotify_event *e = (const struct inotify_event *)(void *)p;
                if (e->len && strncmp(e->name, "doc", 3) != 0)
                    fail_msg("document %d: the loader opened or read %s/%s", k, dir, e->name);
                p += sizeof *e + e->len;
            }
#endif
    }
#ifdef __linux__
    close(watch);
#endif
}

/* the host's own external entity loader is never called, and the settings stay */
static void test_host_loader(void **state)
{
    (void)state;
    const xmlExternalEntityLoader old = xmlGetExternalEntityLoader();
    xmlSetExternalEntityLoader(counting_loader);
    char xml[1024];
    snprintf(xml, sizeof xml,
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot SYSTEM \"file://%s\" [<!ENTITY x SYSTEM \"file://%s\">]>\n"
             "<robot name=\"r\"><link name=\"world\"/><link name=\"a\">&x;</link></robot>", dtd, secret);
    load_result r = load_quietly(NULL, xml, NULL);
    assert_int_equal(r.status, VT_ERR_XML);
    snprintf(xml, sizeof xml,
             "<?xml version=\"1.0\"?>\n<!DOCTYPE robot SYSTEM \"file://%s\">\n"
             "<robot name=\"r\"><link name=\"world\"/><link name=\"a\"/>"
             "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/><child link=\"a\"/></joint></robot>", dtd);
    r = load_quietly(NULL, xml, NULL);
    assert_int_equal(r.status, VT_OK);
    vt_builder_free(r.builder);
    xmlSetExternalEntityLoader(old);
    assert_int_equal(host_loader_calls, 0);
}

int main(void)
{
    /* the references: loaded before the host changes anything */
    const vt_urdf_options opt = double_link_options();
    vt_builder *b = NULL;
    char msg[256];
    if (vt_urdf_builder(&b, VT_TEST_URDF_DIR "/double_link.urdf", &opt, msg) != VT_OK ||
        fingerprint_of(b, &reference_plain)) {
        fprintf(stderr, "double_link.urdf with libxml2's defaults: %s\n", msg);
        return 1;
    }
    vt_builder_free(b);
    if (vt_urdf_builder_string(&b, robot_string, NULL, msg) != VT_OK || fingerprint_of(b, &reference_string)) {
        fprintf(stderr, "the string with libxml2's defaults: %s\n", msg);
        return 1;
    }
    vt_builder_free(b);
    set_host_defaults();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_normal_robot),
        cmocka_unit_test(test_local_files),
        cmocka_unit_test(test_host_loader),
    };
    return cmocka_run_group_tests(tests, setup_files, teardown_files);
}
