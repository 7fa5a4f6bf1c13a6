/* TRANSACT_RUN: a change carried out as one transaction (reference §5, docs/host-link.md §5.6).
 *
 *   interlock → write → read back and compare → restore on a mismatch → release
 *
 * As bus/arbitrator/change/transactions.py: every present device whose outputs feed a terminal
 * channel before or after the change is held with Suspend Device (2000 ms) when the change
 * moves links or parameters; one that refuses stops the change before anything is written.
 * Writes: link actions in order, parameters, the stored configuration (the two-slot write),
 * the policy.  Verify: the link table against the links wanted, each touched input's Data
 * Transfer Enabled and Source's Node Ids read from the device, parameters read back, the
 * memory read back.  On a failure what was there is put back.  The change is read from NVM
 * area 2 (staged by TRANSACT_CHUNK), the result written to area 3 for RESULT_READ.
 */
#include <string.h>
#include "arb.h"
#include "port.h"

#ifdef __AVR__
#  define MAX_TXN_LINKS 16
#  define MAX_TXN_PARAMS 4
#else
#  define MAX_TXN_LINKS 64
#  define MAX_TXN_PARAMS 16
#endif

static link_t before[MAX_LINKS], after[MAX_LINKS];
static uint16_t nbefore, nafter;
static struct { uint8_t op; link_t link; } acts[MAX_TXN_LINKS];
static uint16_t nacts;
static struct { dev_key_t key; uint8_t chan, param; uint16_t len; uint32_t at; uint16_t old_len; uint8_t old[16]; } params[MAX_TXN_PARAMS];
static uint8_t nparams;
static dev_key_t held[MAX_DEVICES];
static int nheld;
static char action[64], reason[200], note[120];

/* -- reading the staged change ------------------------------------------------------------ */
static uint32_t cur, total;
static int bad;

static void take(uint8_t *out, uint32_t n)
{
    if (bad || cur + n > total) { bad = 1; if (out) memset(out, 0, n); return; }
    if (out && port_nvm_read(2, cur, out, n)) bad = 1;
    cur += n;
}
static uint8_t u8(void) { uint8_t v; take(&v, 1); return v; }
static uint16_t u16(void) { uint8_t v[2]; take(v, 2); return get16(v); }

/* -- writing the result ------------------------------------------------------------------ */
static uint32_t rlen;
static uint16_t rcrc;
static int rbad;

static void out(const void *p, uint32_t n)
{
    if (port_nvm_write(3, rlen, (const uint8_t *)p, n)) rbad = 1;
    rcrc = crc16_update(rcrc, (const uint8_t *)p, n);
    rlen += n;
}
static void out8(uint8_t v) { out(&v, 1); }
static void out16(uint16_t v) { uint8_t b[2]; put16(b, v); out(b, 2); }
static void out_str8(const char *s) { uint8_t n = (uint8_t)strlen(s); out8(n); out(s, n); }
static void out_str16(const char *s) { uint16_t n = (uint16_t)strlen(s); out16(n); out(s, n); }
static void out_links(const link_t *l, uint16_t n)
{
    uint8_t b[14];
    out16(n);
    for (uint16_t i = 0; i < n; i++) { put_ref(b, &l[i].out); put_ref(b + 7, &l[i].in); out(b, 14); }
}
static void out_keys(const dev_key_t *k, int n)
{
    uint8_t b[6];
    out8((uint8_t)n);
    for (int i = 0; i < n; i++) { put16(b, k[i].vid); put16(b + 2, k[i].pid); put16(b + 4, k[i].serial); out(b, 6); }
}

/* The CRC record of the stored configuration (the one before End), as the history keeps it. */
static int stored_crc(uint16_t *crc)
{
    uint32_t len;
    uint8_t b[2];
    if (mem_current(&len, 0, 0) < 0 || len < 6 || mem_read(len - 5, b, 2)) return 0;
    *crc = get16(b);
    return 1;
}

static void sort_links(link_t *l, uint16_t n)
{
    for (uint16_t i = 1; i < n; i++) {
        link_t x = l[i];
        int j = i;
        while (j > 0 && link_cmp(&l[j - 1], &x) > 0) { l[j] = l[j - 1]; j--; }
        l[j] = x;
    }
}

static int in_set(const link_t *set, uint16_t n, const link_t *l)
{
    for (uint16_t i = 0; i < n; i++) if (!link_cmp(&set[i], l)) return i;
    return -1;
}

static void add_feeder(const link_t *l)
{
    int ic = ch_find(&l->in);
    if (ic < 0 || !(g_ch[ic].type & TYPE_TERMINAL) || !ref_present(&l->out, DIR_OUT)) return;
    dev_key_t k = { l->out.vid, l->out.pid, l->out.serial };
    for (int i = 0; i < nheld; i++) if (key_eq(&held[i], &k)) return;
    if (nheld < MAX_DEVICES) held[nheld++] = k;
}

static int check_change(void)
{
    for (uint16_t n = 0; n < nacts; n++) {
        const link_t *l = &acts[n].link;
        int o = ch_find(&l->out), i = ch_find(&l->in);
        if (o < 0 || g_ch[o].dir != DIR_OUT || i < 0 || g_ch[i].dir != DIR_IN) {
            fmt_text(reason, sizeof reason, "action %u (%s %r -> %r): not an output and an input "
                     "channel of the system; nothing was written", n + 1,
                     acts[n].op == 1 ? "add" : "remove", &l->out, &l->in);
            return 1;
        }
        if (acts[n].op == 1 && link_find(l) < 0 && (!ch_present(o) || !ch_present(i))) {
            fmt_text(reason, sizeof reason, "action %u (add %r -> %r): an end is not on the bus; "
                     "nothing was written", n + 1, &l->out, &l->in);
            return 1;
        }
    }
    for (int p = 0; p < nparams; p++) {
        int d = dev_find(&params[p].key);
        if (d < 0 || !g_dev[d].present) {
            fmt_text(reason, sizeof reason, "device %k is not on the bus; nothing was written",
                     &params[p].key);
            return 1;
        }
    }
    return 0;
}

static int verify(void)
{
    uint8_t v[16];
    uint16_t n;
    if (g_nlinks != nafter) { fmt_text(reason, sizeof reason, "the links do not read back as written"); return 1; }
    for (uint16_t i = 0; i < nafter; i++)
        if (link_find(&after[i]) < 0) { fmt_text(reason, sizeof reason, "link %r -> %r is missing", &after[i].out, &after[i].in); return 1; }
    for (uint16_t a = 0; a < nacts; a++) {
        const ch_ref_t *in = &acts[a].link.in;
        int ic = ch_find(in);
        if (ic < 0 || !ch_present(ic)) continue;
        int dev = g_ch[ic].dev;
        if (arb_get_param(dev, 4, in->index, v, sizeof v, &n)) { fmt_text(reason, sizeof reason, "reading back failed"); return 1; }
        int src = link_source_of(in, 1);
        if (src < 0) {
            if (n && v[0]) { fmt_text(reason, sizeof reason, "input %r still receives data after its link was removed", in); return 1; }
            continue;
        }
        if (!n || v[0] != 1) { fmt_text(reason, sizeof reason, "input %r does not receive data", in); return 1; }
        if (arb_get_param(dev, 7, in->index, v, sizeof v, &n)) { fmt_text(reason, sizeof reason, "reading back failed"); return 1; }
        const ch_ref_t *out_ref = &g_links[src].out;
        dev_key_t ok = { out_ref->vid, out_ref->pid, out_ref->serial };
        int od = dev_find(&ok);
        if (n < 2 || od < 0 || v[0] != g_dev[od].node_id || v[1] != node_output_id(out_ref)) {
            fmt_text(reason, sizeof reason, "input %r listens to other node IDs than %r", in, out_ref);
            return 1;
        }
    }
    for (int p = 0; p < nparams; p++) {
        static uint8_t want[VALUE_MAX], got[VALUE_MAX];
        int d = dev_find(&params[p].key);
        if (port_nvm_read(2, params[p].at, want, params[p].len) ||
            arb_get_param(d, params[p].param, params[p].chan, got, VALUE_MAX, &n) ||
            n != params[p].len || memcmp(want, got, n)) {
            fmt_text(reason, sizeof reason, "parameter %u of %k channel %u does not read back as written",
                     params[p].param, &params[p].key, params[p].chan);
            return 1;
        }
    }
    return 0;
}

static void restore(int cfg_written, int cfg_had, uint32_t cfg_len, uint16_t cfg_flags,
                    int policy_written, int policy_before)
{
    char why[60];
    for (int i = (int)g_nlinks - 1; i >= 0; i--) {
        link_t l = g_links[i];
        if (in_set(before, nbefore, &l) < 0) arb_remove_link(&l, why, sizeof why);
    }
    for (uint16_t i = 0; i < nbefore; i++)
        if (link_find(&before[i]) < 0) arb_add_link(&before[i], why, sizeof why);
    for (int p = nparams - 1; p >= 0; p--) {
        int d = dev_find(&params[p].key);
        if (d >= 0 && params[p].old_len) arb_set_param(d, params[p].param, params[p].chan, params[p].old, params[p].old_len);
    }
    if (cfg_written) {
        if (cfg_had) { mem_begin(); mem_commit(cfg_len, cfg_flags); }   /* the other slot holds it */
        else mem_write_policy(mem_policy_autoconfigure());
    }
    if (policy_written) mem_write_policy(policy_before);
}

/* -- replaced parts (engine/replaced.py) ---------------------------------------------------
 * After a verified change an absent part whose every role a present part now holds is no
 * longer missing but replaced: forgotten (out of the tables, its dead links with it), noted in
 * the result ("replaced A by B", the fitting history's) and said as DEVICE_REPLACED (host-link
 * §5.7).  Its roles are the links on the bus before and after the change and those of the
 * configuration stored before it (read from its slot into g_stored). */
static uint8_t rep_old[MAX_DEVICES], rep_new[MAX_DEVICES];
static int nrep;

static int dev_of_ref(const ch_ref_t *r)
{
    dev_key_t k = { r->vid, r->pid, r->serial };
    return dev_find(&k);
}

/* Per link of g_links, looked up once per judgement (each lookup scans the tables): its
 * input's and output's channel slots (-1: not in the tables) and which ends are on the bus. */
static int16_t lk_in[MAX_LINKS], lk_out[MAX_LINKS];
static uint8_t lk_live[MAX_LINKS];   /* bit 0: the input is on the bus, bit 1: the output */

static void look_up_links(void)
{
    for (uint16_t i = 0; i < g_nlinks; i++) {
        const link_t *l = &g_links[i];
        lk_in[i] = (int16_t)ch_find(&l->in);
        lk_out[i] = (int16_t)ch_find(&l->out);
        lk_live[i] = (uint8_t)(ref_present(&l->in, DIR_IN) | (ref_present(&l->out, DIR_OUT) << 1));
    }
}

/* Marks in `by` the present devices that hold `old`'s end of `role` now; -1 when it is not its
 * role or its other end is not on the bus either (nothing to judge), else how many hold it. */
static int holders(const link_t *role, int old, uint8_t *by)
{
    int in_dev = dev_of_ref(&role->in), out_dev = dev_of_ref(&role->out), n = 0;
    memset(by, 0, MAX_DEVICES);
    if (in_dev == old && out_dev != old) {
        if (!ref_present(&role->out, DIR_OUT)) return -1;
        int other = ch_find(&role->out), mine = ch_find(&role->in);
        uint16_t profile = mine >= 0 ? g_ch[mine].profile : 0;
        for (int pass = profile ? 0 : 1; pass < 2 && !n; pass++)   /* alike first, else any fed */
            for (uint16_t i = 0; i < g_nlinks; i++) {
                if (lk_out[i] != other || !(lk_live[i] & 1)) continue;
                int d = g_ch[lk_in[i]].dev;
                if (d == old || (!pass && g_ch[lk_in[i]].profile != profile)) continue;
                n += !by[d]; by[d] = 1;
            }
        return n;
    }
    if (out_dev == old && in_dev != old) {
        if (!ref_present(&role->in, DIR_IN)) return -1;
        int other = ch_find(&role->in);
        for (uint16_t i = 0; i < g_nlinks; i++) {
            if (lk_in[i] != other || !(lk_live[i] & 2)) continue;
            int d = g_ch[lk_out[i]].dev;
            if (d == old) continue;
            n += !by[d]; by[d] = 1;
        }
        return n;
    }
    return -1;
}

static int names_dev(const link_t *l, int d)
{
    return dev_of_ref(&l->out) == d || dev_of_ref(&l->in) == d;
}

/* Which absent parts are replaced, and by whom (rep_old / rep_new), as PDCP Studio's arbitrator
 * judges it: only by a change that made links touching the two or stored a configuration,
 * and never a part that configuration names. */
static void find_replaced(int has_cfg, uint32_t cfg_at, uint32_t cfg_len)
{
    static uint8_t takers[MAX_DEVICES], by[MAX_DEVICES];
    uint16_t nroles = (uint16_t)(nbefore + g_nlinks + g_nstored);
    nrep = 0;
    look_up_links();
    for (int d = 0; d < MAX_DEVICES; d++) {
        if (!g_dev[d].used || !g_dev[d].in_system || g_dev[d].present) continue;
        int judged = 0, taken = 0;
        memset(takers, 0, sizeof takers);
        for (uint16_t i = 0; i < nroles; i++) {
            link_t stored;
            const link_t *role = i < nbefore ? &before[i] : i < nbefore + g_nlinks ?
                &g_links[i - nbefore] : &stored;
            if (role == &stored) {
                const stored_link_t *sl = &g_stored[i - nbefore - g_nlinks];
                stored.out = sl->out; stored.in = sl->in;
                if (link_find(&stored) >= 0) continue;
                int dup = 0;
                for (uint16_t j = 0; j < i - nbefore - g_nlinks && !dup; j++)
                    dup = !ref_cmp(&g_stored[j].out, &sl->out) && !ref_cmp(&g_stored[j].in, &sl->in);
                if (dup) continue;
            }
            if (i >= nbefore && in_set(before, nbefore, role) >= 0) continue;
            int n = holders(role, d, by);
            if (n < 0) continue;
            judged++;
            if (n) taken++;
            for (int k = 0; k < MAX_DEVICES; k++) takers[k] = (uint8_t)(takers[k] + by[k]);
        }
        if (!judged || taken != judged) continue;
        int best = -1;
        for (int k = 0; k < MAX_DEVICES; k++)
            if (takers[k] && (best < 0 || takers[k] > takers[best] ||
                              (takers[k] == takers[best] && key_cmp(&g_dev[k].key, &g_dev[best].key) < 0)))
                best = k;
        int made = has_cfg;
        for (uint16_t a = 0; a < nacts && !made; a++)
            made = names_dev(&acts[a].link, d) || names_dev(&acts[a].link, best);
        if (made) { rep_old[nrep] = (uint8_t)d; rep_new[nrep] = (uint8_t)best; nrep++; }
    }
    /* never a part the configuration just stored names: that keeps it in the fitting */
    if (has_cfg && !config_decode(2, cfg_at, cfg_len, note, sizeof note))
        for (int r = nrep - 1; r >= 0; r--) {
            int kept = 0;
            for (uint16_t i = 0; i < g_nstored && !kept; i++) {
                dev_key_t o = { g_stored[i].out.vid, g_stored[i].out.pid, g_stored[i].out.serial };
                dev_key_t n = { g_stored[i].in.vid, g_stored[i].in.pid, g_stored[i].in.serial };
                kept = key_eq(&o, &g_dev[rep_old[r]].key) || key_eq(&n, &g_dev[rep_old[r]].key);
            }
            if (kept) { nrep--; for (int k = r; k < nrep; k++) { rep_old[k] = rep_old[k + 1]; rep_new[k] = rep_new[k + 1]; } }
        }
    for (int r = 0; r < nrep; r++) {   /* forget them, with their dead links */
        for (int i = (int)g_nlinks - 1; i >= 0; i--)
            if (names_dev(&g_links[i], rep_old[r])) link_del(i);
        g_dev[rep_old[r]].in_system = 0;
        port_log("a replaced part is forgotten");
    }
}

int txn_run(uint32_t len, uint32_t *result_len, uint16_t *result_crc, char *why, int room)
{
    uint8_t b[16];
    cur = 0; total = len; bad = 0;
    uint8_t n8 = u8();
    take(0, 0);
    memset(action, 0, sizeof action);
    if (n8 < sizeof action) take((uint8_t *)action, n8); else { take((uint8_t *)action, sizeof action - 1); take(0, n8 - (sizeof action - 1)); }
    uint16_t nl = u16();
    if (nl > MAX_TXN_LINKS) { fmt_text(why, room, "a change of %u link actions is more than this arbitrator takes (%u)", nl, MAX_TXN_LINKS); return 0x0C; }
    nacts = nl;
    for (uint16_t i = 0; i < nl && !bad; i++) {
        acts[i].op = u8();
        take(b, 14);
        get_ref(b, &acts[i].link.out); get_ref(b + 7, &acts[i].link.in);
        take(0, u8());
        if (acts[i].op != 1 && acts[i].op != 2) { fmt_text(why, room, "link op %u is neither 1 (add) nor 2 (remove)", acts[i].op); return 0x02; }
    }
    nparams = u8();
    if (nparams > MAX_TXN_PARAMS) { fmt_text(why, room, "too many parameters in one change"); return 0x0C; }
    for (int p = 0; p < nparams && !bad; p++) {
        take(b, 8);
        params[p].key.vid = get16(b); params[p].key.pid = get16(b + 2); params[p].key.serial = get16(b + 4);
        params[p].chan = b[6]; params[p].param = b[7];
        params[p].len = u16();
        params[p].at = cur;
        if (params[p].len > VALUE_MAX) { fmt_text(why, room, "a parameter value is too large"); return 0x0C; }
        take(0, params[p].len);
    }
    uint8_t has_cfg = u8();
    uint32_t cfg_at = 0, cfg_len = 0;
    if (has_cfg) { cfg_len = u16(); cfg_at = cur; take(0, cfg_len); }
    uint8_t policy = u8();
    if (bad || cur != total) { fmt_text(why, room, "the change does not decode (%u of %u bytes)", (unsigned)cur, (unsigned)total); return 0x02; }
    if (has_cfg && config_decode(2, cfg_at, cfg_len, note, sizeof note)) { fmt_text(why, room, "%s", note); return 0x0E; }

    /* before, after */
    memcpy(before, g_links, sizeof(link_t) * g_nlinks);
    nbefore = g_nlinks;
    sort_links(before, nbefore);
    memcpy(after, before, sizeof(link_t) * nbefore);
    nafter = nbefore;
    for (uint16_t i = 0; i < nacts; i++) {
        int k = in_set(after, nafter, &acts[i].link);
        if (acts[i].op == 1 && k < 0 && nafter < MAX_LINKS) after[nafter++] = acts[i].link;
        else if (acts[i].op == 2 && k >= 0) { for (uint16_t j = (uint16_t)k; j + 1 < nafter; j++) after[j] = after[j + 1]; nafter--; }
    }
    sort_links(after, nafter);
    uint16_t crc_before = 0, crc_after;
    int had_crc = stored_crc(&crc_before);
    uint32_t old_len; uint16_t old_flags;
    int old_slot = mem_current(&old_len, 0, &old_flags), had_cfg = old_slot >= 0;
    int pol_before = mem_policy_autoconfigure();
    uint8_t status = 3, step = 0xFF, verified = 0;
    const char *interlock = "not needed";
    char interlock_text[40];
    reason[0] = 0;
    nheld = 0;
    nrep = 0;
    int cfg_written = 0, policy_written = 0;

    if (!g_may_write) {
        step = 0;
        if (g_other_heard) fmt_text(reason, sizeof reason, "another arbitrator is on the bus: nothing was written");
        else fmt_text(reason, sizeof reason, "the arbitrator is still listening for another one on the bus: nothing was written");
    } else if (check_change()) {
        step = 0;
    } else {
        if (nacts || nparams) {
            for (uint16_t i = 0; i < nbefore; i++) add_feeder(&before[i]);
            for (uint16_t i = 0; i < nafter; i++) add_feeder(&after[i]);
        }
        int refused = 0;
        if (arb_hold(held, nheld, &refused)) {
            step = 2;
            fmt_text(reason, sizeof reason, "device %k did not suspend; nothing was written", &held[refused]);
            fmt_text(interlock_text, sizeof interlock_text, "refused by %k", &held[refused]);
            interlock = interlock_text;
            nheld = 0;
        } else {
            if (nheld) {
                fmt_text(interlock_text, sizeof interlock_text, "held %u device%s", (unsigned)nheld, nheld == 1 ? "" : "s");
                interlock = interlock_text;
            }
            int failed = 0;
            for (int p = 0; p < nparams && !failed; p++) {   /* what is there, to restore it */
                uint16_t n;
                int d = dev_find(&params[p].key);
                if (arb_get_param(d, params[p].param, params[p].chan, params[p].old, sizeof params[p].old, &n)) n = 0;
                params[p].old_len = n;
            }
            for (uint16_t i = 0; i < nacts && !failed; i++) {
                char w[80];
                int exists = link_find(&acts[i].link) >= 0;
                int st = 0;
                if (acts[i].op == 1 && !exists) st = arb_add_link(&acts[i].link, w, sizeof w);
                else if (acts[i].op == 2 && exists) st = arb_remove_link(&acts[i].link, w, sizeof w);
                if (st) { failed = 1; fmt_text(reason, sizeof reason, "%s", w); }
            }
            for (int p = 0; p < nparams && !failed; p++) {
                static uint8_t v[VALUE_MAX];
                int d = dev_find(&params[p].key);
                if (arb_managed(d, params[p].param, params[p].chan)) {
                    failed = 1;
                    fmt_text(reason, sizeof reason, "parameter %u of channel %u is managed by the arbitrator", params[p].param, params[p].chan);
                } else if (port_nvm_read(2, params[p].at, v, params[p].len) ||
                           arb_set_param(d, params[p].param, params[p].chan, v, params[p].len)) {
                    failed = 1;
                    fmt_text(reason, sizeof reason, "parameter %u of %k: the device did not take it", params[p].param, &params[p].key);
                }
            }
            if (!failed && has_cfg) {
                mem_begin();
                cfg_written = 1;
                if (mem_copy_area(2, cfg_at, cfg_len) || mem_commit(cfg_len, old_flags)) {
                    failed = 1;
                    fmt_text(reason, sizeof reason, "the memory write failed");
                }
            }
            if (!failed && policy != 0xFF) {
                policy_written = 1;
                if (mem_write_policy(policy)) { failed = 1; fmt_text(reason, sizeof reason, "the policy write failed"); }
            }
            if (failed) step = 3;
            else if (verify()) step = 4;
            else if (has_cfg) {
                uint32_t l2; uint16_t c2, c1 = 0xFFFF;
                uint8_t buf[64];
                mem_current(&l2, &c2, 0);
                for (uint32_t off = 0; off < cfg_len; off += sizeof buf) {
                    uint32_t k = cfg_len - off < sizeof buf ? cfg_len - off : sizeof buf;
                    port_nvm_read(2, cfg_at + off, buf, k);
                    c1 = crc16_update(c1, buf, k);
                }
                if (l2 != cfg_len || c1 != c2) { step = 4; fmt_text(reason, sizeof reason, "the stored configuration does not verify when read back"); }
            }
            if (step == 0xFF && policy != 0xFF && mem_policy_autoconfigure() != policy) {
                step = 4; fmt_text(reason, sizeof reason, "the policy does not read back as written");
            }
            if (step == 0xFF) {
                status = 0; verified = 1;
            } else {
                restore(cfg_written, had_cfg && old_len, old_len, old_flags, policy_written, pol_before);
                status = 4;
                int n = (int)strlen(reason);
                fmt_text(reason + n, (int)sizeof reason - n, "; what was there is restored");
            }
            arb_release(held, nheld);
            if (status == 0) {
                /* the configuration stored before: in its slot still, unless a policy write
                 * after a configuration write took that slot too */
                if (!had_cfg || !old_len || (cfg_written && policy_written) ||
                    mem_decode_slot(old_slot, old_len, note, sizeof note))
                    g_nstored = 0;
                find_replaced(has_cfg, cfg_at, cfg_len);
            }
        }
    }
    /* the result */
    rlen = 0; rcrc = 0xFFFF; rbad = 0;
    int has_after = stored_crc(&crc_after);
    uint8_t head[3] = { status, step, verified };
    out(head, 3);
    out8((uint8_t)had_crc); out16(had_crc ? crc_before : 0);
    out8((uint8_t)has_after); out16(has_after ? crc_after : 0);
    out8((uint8_t)pol_before); out8((uint8_t)mem_policy_autoconfigure());
    out_str8(action);
    out_str16(reason);
    out_str8(interlock);
    out_links(before, nbefore);
    memcpy(after, g_links, sizeof(link_t) * g_nlinks);
    nafter = g_nlinks;
    sort_links(after, nafter);
    out_links(after, nafter);
    out_keys(held, nheld);
    {
        static dev_key_t present[MAX_DEVICES];
        int np = 0;
        for (int d = 0; d < MAX_DEVICES; d++) {
            if (!g_dev[d].used || !g_dev[d].present) continue;
            int j = np++;
            while (j > 0 && key_cmp(&present[j - 1], &g_dev[d].key) > 0) { present[j] = present[j - 1]; j--; }
            present[j] = g_dev[d].key;
        }
        out_keys(present, np);
    }
    out8((uint8_t)nrep);   /* notes: "replaced A by B" (the fitting history's) */
    for (int r = 0; r < nrep; r++) {
        fmt_text(note, sizeof note, "replaced %k by %k", &g_dev[rep_old[r]].key, &g_dev[rep_new[r]].key);
        out_str16(note);
    }
    if (rbad) { fmt_text(why, room, "the result could not be written to memory"); return 0x13; }
    *result_len = rlen;
    *result_crc = rcrc;
    for (int r = 0; r < nrep; r++) {   /* DEVICE_REPLACED: old key, new key (§5.7) */
        uint8_t ev[13];
        const dev_key_t *k[2] = { &g_dev[rep_old[r]].key, &g_dev[rep_new[r]].key };
        ev[0] = 0x4C;
        for (int e = 0; e < 2; e++) { put16(ev + 1 + 6 * e, k[e]->vid); put16(ev + 3 + 6 * e, k[e]->pid); put16(ev + 5 + 6 * e, k[e]->serial); }
        hl_event(ev, 13);
    }
    {
        uint8_t ev[1 + 1 + 62];
        int k = (int)strlen(action);
        if (k > 62) k = 62;
        ev[0] = 0x4A; ev[1] = status;
        memcpy(ev + 2, action, (size_t)k);
        hl_event(ev, 2 + k);
    }
    return 0;
}
