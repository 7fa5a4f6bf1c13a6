/* The device profile layer (thesis listings 4.1–4.9, reference §2 with its Decisions).
 *
 * The same algorithm as PDCP Studio's engine (engine/layer.py, procedures.py, similarity.py,
 * candidates.py): a plan is worked out on an overlay of the link table (the layer's own link
 * set and a journal of actions, so a rollback undoes exactly what one intelligently_connect
 * and the calls under it made), then written on the bus with the motion interlock holding the
 * devices whose outputs feed a terminal channel before or after the plan.
 *
 * The duty cycle also repairs dead links left by an earlier cycle (see profile_duty_cycle).
 *
 * Present: the device is on the bus (an output also needs a node ID).  Dead link: an end not
 * present; it carries no data, does not count as a source nor towards sole access, and is
 * removed (superseded) when its input gets a new source.
 */
#include <string.h>
#include "arb.h"
#include "port.h"

#define OP_ADD 1
#define OP_REMOVE 2

static link_t L[MAX_LINKS];          /* the layer's links */
static uint16_t nL;
static struct { uint8_t op; link_t link; } act[MAX_ACTIONS];
static uint16_t nact;
static uint8_t overflow;
static stored_link_t cfg[MAX_STORED_LINKS];
static uint16_t ncfg;
static uint8_t was_present[(MAX_CHANNELS + 7) / 8];

/* -- facts ------------------------------------------------------------------------------- */
static int present(const ch_ref_t *r, uint8_t dir) { return ref_present(r, dir); }
static int live(const link_t *l) { return present(&l->out, DIR_OUT) && present(&l->in, DIR_IN); }

static int l_find(const link_t *l)
{
    for (uint16_t i = 0; i < nL; i++) if (!link_cmp(&L[i], l)) return i;
    return -1;
}

static int has_source(const ch_ref_t *in)
{
    for (uint16_t i = 0; i < nL; i++)
        if (!ref_cmp(&L[i].in, in) && live(&L[i])) return 1;
    return 0;
}

static int is_sole(const ch_ref_t *in)
{
    int c = ch_find(in);
    return c >= 0 && (g_ch[c].type & TYPE_SOLE);
}

static int sole_fed(const ch_ref_t *out)
{
    for (uint16_t i = 0; i < nL; i++)
        if (!ref_cmp(&L[i].out, out) && live(&L[i]) && is_sole(&L[i].in)) return 1;
    return 0;
}

static int depth_of(uint16_t a, uint16_t b)
{
    int d = 0;
    for (int s = 12; s >= 0; s -= 4) {
        uint16_t x = (uint16_t)(a >> s & 0xF), y = (uint16_t)(b >> s & 0xF);
        if (x != y || !x) break;
        d++;
    }
    return d;
}

static int type_score(uint16_t a, uint16_t b)
{
    uint16_t diff = (uint16_t)(a ^ b);
    return (diff & 0x0C00 ? 0 : 4) + (diff & 0x3000 ? 0 : 2) + (diff & 0xC000 ? 0 : 1);
}

static int similarity(uint16_t at, uint16_t ap, uint16_t bt, uint16_t bp)
{
    return depth_of(ap, bp) * 8 + type_score(at, bt);
}

static int link_similarity(const link_t *l)
{
    int o = ch_find(&l->out), i = ch_find(&l->in);
    if (o < 0 || i < 0) return 0;
    return similarity(g_ch[o].type, g_ch[o].profile, g_ch[i].type, g_ch[i].profile);
}

/* Listing 4.8: the most similar present, free channel of `dir`, not on `exclude`, sharing at
 * least the root component; ties by lower profile, then lower reference. -1: none. */
static int find_similar(uint8_t dir, uint16_t qt, uint16_t qp, const dev_key_t *exclude,
                        int sole)
{
    int best = -1, best_score = -1;
    ch_ref_t best_ref, r;
    for (int c = 0; c < MAX_CHANNELS; c++) {
        if (!g_ch[c].used || g_ch[c].dir != dir || !ch_present(c)) continue;
        if (exclude && key_eq(&g_dev[g_ch[c].dev].key, exclude)) continue;
        int depth = depth_of(qp, g_ch[c].profile);
        if (depth < 1) continue;
        ch_ref(c, &r);
        if (dir == DIR_OUT ? (sole && sole_fed(&r)) : has_source(&r)) continue;
        int score = depth * 8 + type_score(qt, g_ch[c].type);
        if (best < 0 || score > best_score ||
            (score == best_score && (g_ch[c].profile < g_ch[best].profile ||
                                     (g_ch[c].profile == g_ch[best].profile &&
                                      ref_cmp(&r, &best_ref) < 0)))) {
            best = c; best_score = score; best_ref = r;
        }
    }
    return best;
}

static int find_output_for(const ch_ref_t *in)
{
    int c = ch_find(in);
    dev_key_t k = { in->vid, in->pid, in->serial };
    return find_similar(DIR_OUT, g_ch[c].type, g_ch[c].profile, &k, (g_ch[c].type & TYPE_SOLE) != 0);
}

/* -- journalled changes -------------------------------------------------------------------- */
static void record(uint8_t op, const link_t *l)
{
    if (nact >= MAX_ACTIONS) { overflow = 1; return; }
    act[nact].op = op; act[nact].link = *l; nact++;
}

static void l_add(const link_t *l)
{
    if (nL >= MAX_LINKS) { overflow = 1; return; }
    L[nL++] = *l;
    record(OP_ADD, l);
}

static void l_remove(const link_t *l)
{
    int i = l_find(l);
    if (i < 0) return;
    for (int j = i; j + 1 < (int)nL; j++) L[j] = L[j + 1];
    nL--;
    record(OP_REMOVE, l);
}

static void rollback(uint16_t mark)
{
    while (nact > mark) {
        nact--;
        link_t l = act[nact].link;
        if (act[nact].op == OP_ADD) {
            int i = l_find(&l);
            if (i >= 0) { for (int j = i; j + 1 < (int)nL; j++) L[j] = L[j + 1]; nL--; }
        } else if (nL < MAX_LINKS) {
            L[nL++] = l;
        }
    }
}

/* -- listing 4.4 ------------------------------------------------------------------------- */
#define REFUSED 0
#define MADE 1
#define EXISTS 2

static int connect(const link_t *l)
{
    if (!present(&l->out, DIR_OUT) || !present(&l->in, DIR_IN)) return REFUSED;
    if (l_find(l) >= 0) return EXISTS;
    if (has_source(&l->in)) return REFUSED;
    if (is_sole(&l->in) && sole_fed(&l->out)) return REFUSED;
    for (;;) {   /* dead links into the input are superseded, in sorted order */
        int best = -1;
        for (uint16_t i = 0; i < nL; i++)
            if (!ref_cmp(&L[i].in, &l->in) && (best < 0 || link_cmp(&L[i], &L[best]) < 0))
                best = i;
        if (best < 0) break;
        link_t dead = L[best];
        l_remove(&dead);
    }
    l_add(l);
    return MADE;
}

/* -- listing 4.5 ------------------------------------------------------------------------- */
static ch_ref_t visited[MAX_VISIT];
static uint16_t nvisited;

static int was_visited(const ch_ref_t *r)
{
    for (uint16_t i = 0; i < nvisited; i++) if (!ref_cmp(&visited[i], r)) return 1;
    return 0;
}

static void visit(const ch_ref_t *r)
{
    if (!was_visited(r) && nvisited < sizeof visited / sizeof visited[0]) visited[nvisited++] = *r;
}

static int intelligently_connect(const link_t *l, int top)
{
    if (top) nvisited = 0;
    uint16_t mark = nact;
    if (connect(l) == REFUSED) return 0;
    visit(&l->in);
    int oc = ch_find(&l->out), ic = ch_find(&l->in);
    /* the output's required, the input's required, the output's desired, the input's desired */
    const ch_ref_t *owners[4] = { &l->out, &l->in, &l->out, &l->in };
    uint32_t lists[4] = { g_ch[oc].req, g_ch[ic].req, g_ch[oc].des, g_ch[ic].des };
    uint32_t seen_o = 0, seen_i = 0;     /* inputs named so far, by owner device */
    dev_key_t ko = { l->out.vid, l->out.pid, l->out.serial }, ki = { l->in.vid, l->in.pid, l->in.serial };
    int same = key_eq(&ko, &ki);
    for (int w = 0; w < 4; w++) {
        int required = w < 2;
        uint32_t *seen = (w % 2 == 0 || same) ? &seen_o : &seen_i;
        for (uint8_t idx = 0; idx < 32; idx++) {
            if (!(lists[w] & (1u << idx))) continue;
            ch_ref_t ref = *owners[w];
            ref.index = idx;
            if (*seen & (1u << idx)) continue;
            *seen |= 1u << idx;
            int is_in = present(&ref, DIR_IN);
            if (is_in && has_source(&ref)) continue;
            int ok = 0;
            if (is_in && !was_visited(&ref)) {
                visit(&ref);
                int found = find_output_for(&ref);
                if (found >= 0) {
                    link_t sub;
                    ch_ref(found, &sub.out);
                    sub.in = ref;
                    ok = intelligently_connect(&sub, 0);
                }
            }
            if (!ok && required) {
                rollback(mark);
                return 0;
            }
        }
    }
    return 1;
}

/* -- procedures ------------------------------------------------------------------------- */
static void implement(void)      /* listing 4.3 over cfg[] */
{
    for (uint16_t n = 0; n < ncfg; n++) {
        link_t l = { cfg[n].out, cfg[n].in };
        int ic = ch_find(&l.in);
        if (ic >= 0 && (g_ch[ic].type & TYPE_TERMINAL)) intelligently_connect(&l, 1);
        else connect(&l);
    }
}

static int involves_missing(void)
{
    for (uint16_t n = 0; n < ncfg; n++)
        if (!present(&cfg[n].out, DIR_OUT) || !present(&cfg[n].in, DIR_IN)) return 1;
    return 0;
}

typedef struct { link_t link, original; int sim; } repaired_t;
static repaired_t rep[MAX_STORED_LINKS];

static void find_replacements(void)   /* listing 4.6 */
{
    uint16_t nrep = 0;
    for (uint16_t n = 0; n < ncfg; n++) {
        const stored_link_t *sl = &cfg[n];
        int out_ok = present(&sl->out, DIR_OUT), in_ok = present(&sl->in, DIR_IN);
        if ((out_ok && in_ok) || (!out_ok && !in_ok)) continue;
        int found;
        link_t l;
        if (!out_ok) {
            dev_key_t k = { sl->in.vid, sl->in.pid, sl->in.serial };
            found = find_similar(DIR_OUT, sl->out_type, sl->out_profile, &k, is_sole(&sl->in));
            if (found < 0) continue;
            ch_ref(found, &l.out); l.in = sl->in;
        } else {
            dev_key_t k = { sl->out.vid, sl->out.pid, sl->out.serial };
            found = find_similar(DIR_IN, sl->in_type, sl->in_profile, &k, 0);
            if (found < 0) continue;
            l.out = sl->out; ch_ref(found, &l.in);
        }
        rep[nrep].link = l;
        rep[nrep].original.out = sl->out; rep[nrep].original.in = sl->in;
        rep[nrep].sim = link_similarity(&l);
        nrep++;
    }
    for (uint16_t i = 1; i < nrep; i++) {   /* highest similarity first; ties by output, input */
        repaired_t x = rep[i];
        int j = i;
        while (j > 0 && (rep[j - 1].sim < x.sim ||
                         (rep[j - 1].sim == x.sim && link_cmp(&rep[j - 1].link, &x.link) > 0))) {
            rep[j] = rep[j - 1];
            j--;
        }
        rep[j] = x;
    }
    for (uint16_t i = 0; i < nrep; i++) {
        if (!intelligently_connect(&rep[i].link, 1)) continue;
        if (l_find(&rep[i].original) >= 0) l_remove(&rep[i].original);
    }
}

static int terminals[MAX_CHANNELS];

static int unconnected_terminals(void)
{
    int n = 0;
    ch_ref_t r;
    for (int c = 0; c < MAX_CHANNELS; c++) {
        if (!g_ch[c].used || g_ch[c].dir != DIR_IN || !(g_ch[c].type & TYPE_TERMINAL) || !ch_present(c))
            continue;
        ch_ref(c, &r);
        if (has_source(&r)) continue;
        int j = n++;
        while (j > 0) {
            int p = terminals[j - 1];
            ch_ref_t pr;
            ch_ref(p, &pr);
            if (g_ch[p].term_profile < g_ch[c].term_profile ||
                (g_ch[p].term_profile == g_ch[c].term_profile && ref_cmp(&pr, &r) < 0))
                break;
            terminals[j] = p;
            j--;
        }
        terminals[j] = c;
    }
    return n;
}

static void autoconfigure(void)   /* listing 4.7 */
{
    int n = unconnected_terminals();
    for (int i = 0; i < n; i++) {
        ch_ref_t r;
        ch_ref(terminals[i], &r);
        if (has_source(&r)) continue;
        int found = find_output_for(&r);
        if (found < 0) continue;
        link_t l;
        ch_ref(found, &l.out);
        l.in = r;
        intelligently_connect(&l, 1);
    }
}

static void terminals_or_autoconfigure(void)
{
    int n = unconnected_terminals();
    if (!n) return;
    if (mem_policy_autoconfigure()) { autoconfigure(); return; }
    uint8_t msg[1 + 1 + 7 * 24 + 64];
    int k = n > 24 ? 24 : n, len = 2;
    msg[0] = 0x4B; msg[1] = (uint8_t)k;
    for (int i = 0; i < k; i++) { ch_ref_t r; ch_ref(terminals[i], &r); len += put_ref(msg + len, &r); }
    static const char t[] = "autoconfigure is off";
    memcpy(msg + len, t, sizeof t - 1);
    hl_event(msg, len + (int)sizeof t - 1);
}

/* -- writing a plan (with the motion interlock) ---------------------------------------- */
static dev_key_t held[MAX_DEVICES];

static void add_feeder(int *n, const link_t *l)
{
    int ic = ch_find(&l->in);
    if (ic < 0 || !(g_ch[ic].type & TYPE_TERMINAL) || !present(&l->out, DIR_OUT)) return;
    dev_key_t k = { l->out.vid, l->out.pid, l->out.serial };
    for (int i = 0; i < *n; i++) if (key_eq(&held[i], &k)) return;
    if (*n < MAX_DEVICES) held[(*n)++] = k;
}

static void apply_plan(const char *mode)
{
    if (!nact) return;
    int n = 0, refused = 0;
    for (uint16_t i = 0; i < g_nlinks; i++) add_feeder(&n, &g_links[i]);
    for (uint16_t i = 0; i < nL; i++) add_feeder(&n, &L[i]);
    if (arb_hold(held, n, &refused)) {
        char t[120];
        fmt_text(t, sizeof t, "plan %s not written: device %k did not suspend; the prosthesis "
                 "was left as it was", mode, &held[refused]);
        hl_event_error(6, t);
        return;
    }
    for (uint16_t i = 0; i < nact; i++) {
        link_t l = act[i].link;
        if (act[i].op == OP_ADD) {
            int o = ch_find(&l.out), in = ch_find(&l.in);
            if (o < 0 || in < 0 || g_ch[o].dir != DIR_OUT || g_ch[in].dir != DIR_IN) continue;
            if (link_find(&l) >= 0) continue;
            if (present(&l.out, DIR_OUT) && present(&l.in, DIR_IN) && arb_wire_add(&l)) {
                char t[100];
                fmt_text(t, sizeof t, "plan %s: add %r -> %r failed on the bus", mode, &l.out, &l.in);
                hl_event_error(6, t);
                continue;
            }
            if (link_add(&l)) continue;
            hl_event_link(0x43, &l);
        } else {
            int k = link_find(&l);
            if (k < 0) continue;
            link_del(k);
            arb_wire_remove(&l);
            hl_event_link(0x44, &l);
        }
    }
    arb_release(held, n);
    char t[64];
    fmt_text(t, sizeof t, "applied plan %s: %u actions", mode, nact);
    port_log(t);
}

static void begin(void)
{
    memcpy(L, g_links, sizeof(link_t) * g_nlinks);
    nL = g_nlinks;
    nact = 0;
    overflow = 0;
}

static void fill_from_links(void)   /* configuration_from_system: the current links */
{
    ncfg = 0;
    for (uint16_t i = 0; i < g_nlinks && ncfg < MAX_STORED_LINKS; i++) {
        stored_link_t *s = &cfg[ncfg++];
        int o = ch_find(&g_links[i].out), in = ch_find(&g_links[i].in);
        s->out = g_links[i].out; s->in = g_links[i].in; s->config = 1;
        s->out_type = o >= 0 ? g_ch[o].type : 0; s->out_profile = o >= 0 ? g_ch[o].profile : 0;
        s->in_type = in >= 0 ? g_ch[in].type : 0; s->in_profile = in >= 0 ? g_ch[in].profile : 0;
    }
}

static void retrieve(void)   /* from the present inputs' Source fields, in ascending order */
{
    int order[MAX_DEVICES], nd = 0;
    ncfg = 0;
    for (int d = 0; d < MAX_DEVICES; d++) {
        if (!g_dev[d].used || !g_dev[d].present) continue;
        int j = nd++;
        while (j > 0 && key_cmp(&g_dev[order[j - 1]].key, &g_dev[d].key) > 0) { order[j] = order[j - 1]; j--; }
        order[j] = d;
    }
    for (int i = 0; i < nd; i++) {
        int d = order[i];
        for (uint8_t idx = 1; idx <= g_dev[d].nch; idx++) {
            int c = ch_of(d, idx);
            if (c < 0 || g_ch[c].dir != DIR_IN) continue;
            const source_t *s = &g_ch[c].src;
            if ((s->vid == 0xFFFF && s->pid == 0xFFFF && s->serial == 0xFFFF) || s->index == 0xFF)
                continue;
            if (ncfg >= MAX_STORED_LINKS) return;
            stored_link_t *sl = &cfg[ncfg++];
            sl->config = 1;
            ch_ref(c, &sl->in);
            sl->in_type = g_ch[c].type; sl->in_profile = g_ch[c].profile;
            sl->out.vid = s->vid; sl->out.pid = s->pid; sl->out.serial = s->serial;
            sl->out.index = s->index; sl->out_type = s->type; sl->out_profile = s->profile;
        }
    }
}

/* Most links with both ends present, then fewest missing channels, then the first. */
static int choose_configuration(void)
{
    int best = -1, best_whole = -1, best_missing = 0;
    for (uint16_t i = 0; i < g_nstored; i++) {
        int c = g_stored[i].config, seen = 0;
        for (uint16_t j = 0; j < i && !seen; j++) seen = g_stored[j].config == c;
        if (seen) continue;
        int whole = 0, missing = 0;
        ch_ref_t miss[2 * 16];
        int nmiss = 0;
        for (uint16_t j = i; j < g_nstored; j++) {
            if (g_stored[j].config != c) continue;
            int o = present(&g_stored[j].out, DIR_OUT), in = present(&g_stored[j].in, DIR_IN);
            whole += o && in;
            const ch_ref_t *ends[2] = { o ? 0 : &g_stored[j].out, in ? 0 : &g_stored[j].in };
            for (int e = 0; e < 2; e++) {
                if (!ends[e]) continue;
                int dup = 0;
                for (int m = 0; m < nmiss && !dup; m++) dup = !ref_cmp(&miss[m], ends[e]);
                if (dup) continue;
                if (nmiss < 32) miss[nmiss++] = *ends[e];
                missing++;
            }
        }
        if (best < 0 || whole > best_whole || (whole == best_whole && missing < best_missing)) {
            best = c; best_whole = whole; best_missing = missing;
        }
    }
    return best;
}

static void add_missing_devices(void)
{
    for (uint16_t n = 0; n < ncfg; n++) {
        for (int e = 0; e < 2; e++) {
            const ch_ref_t *r = e ? &cfg[n].in : &cfg[n].out;
            dev_key_t k = { r->vid, r->pid, r->serial };
            int d = dev_find(&k);
            if (d >= 0 && (g_dev[d].present || g_dev[d].node_id || g_dev[d].nch)) continue;
            if (d < 0) d = dev_add(&k);
            if (d < 0) return;
            g_dev[d].in_system = 1;
            if (ch_of(d, r->index) >= 0) continue;
            for (int c = 0; c < MAX_CHANNELS; c++) {
                if (g_ch[c].used) continue;
                memset(&g_ch[c], 0, sizeof g_ch[c]);
                g_ch[c].used = 1; g_ch[c].dev = (uint8_t)d; g_ch[c].index = r->index;
                g_ch[c].dir = e ? DIR_IN : DIR_OUT;
                g_ch[c].type = e ? cfg[n].in_type : cfg[n].out_type;
                g_ch[c].profile = e ? cfg[n].in_profile : cfg[n].out_profile;
                g_ch[c].src.vid = g_ch[c].src.pid = g_ch[c].src.serial = 0xFFFF;
                g_ch[c].src.index = 0xFF;
                break;
            }
        }
    }
}

void profile_startup(void)   /* listings 4.1 / 5.1 */
{
    char why[48];
    uint32_t len;
    int stored = 0;
    begin();
    if (mem_current(&len, 0, 0) >= 0 && len && !config_decode(-1, 0, len, why, sizeof why)) {
        int chosen = choose_configuration();
        if (chosen >= 0) {
            stored = 1;
            ncfg = 0;
            for (uint16_t i = 0; i < g_nstored; i++)
                if (g_stored[i].config == chosen) cfg[ncfg++] = g_stored[i];
        }
    }
    if (stored) {
        /* drop the current links the stored configuration does not have (sorted) */
        for (;;) {
            int best = -1;
            for (uint16_t i = 0; i < nL; i++) {
                int keep = 0;
                for (uint16_t n = 0; n < ncfg && !keep; n++)
                    keep = !ref_cmp(&cfg[n].out, &L[i].out) && !ref_cmp(&cfg[n].in, &L[i].in);
                if (!keep && (best < 0 || link_cmp(&L[i], &L[best]) < 0)) best = i;
            }
            if (best < 0) break;
            link_t l = L[best];
            l_remove(&l);
        }
    } else {
        retrieve();
    }
    implement();
    if (involves_missing()) find_replacements();
    terminals_or_autoconfigure();
    if (overflow) hl_event_error(6, "plan startup: a table is full; the plan is cut short");
    apply_plan("startup");
    if (stored) add_missing_devices();
    port_log(stored ? "start-up: the stored configuration" : "start-up: retrieved from the devices");
}

void profile_note_present(void)
{
    for (int c = 0; c < MAX_CHANNELS; c++) {
        if (g_ch[c].used && ch_present(c)) was_present[c / 8] |= (uint8_t)(1 << (c % 8));
        else was_present[c / 8] &= (uint8_t)~(1 << (c % 8));
    }
}

void profile_duty_cycle(void)   /* listing 4.2 */
{
    int gone = 0;
    begin();
    fill_from_links();
    for (int c = 0; c < MAX_CHANNELS; c++)
        if ((was_present[c / 8] & (1 << (c % 8))) && !(g_ch[c].used && ch_present(c))) gone = 1;
    /* A channel that left stays owed a replacement while a dead link still names it, so the
     * result does not depend on whether a replacement joins before or after the duty cycle
     * that followed the departure (PDCP Studio's arbitrator gets the same links when the two
     * fall into one cycle, as in `sim replay thesis-test1 --script hot-swap`). */
    for (uint16_t i = 0; i < g_nlinks && !gone; i++) gone = !live(&g_links[i]);
    if (gone) find_replacements();
    terminals_or_autoconfigure();
    apply_plan("duty-cycle");
}
