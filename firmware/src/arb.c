/* The bus side of the arbitrator: one arbitrator per bus, binding, presence, set-up, links.
 *
 * As PDCP Studio's arbitrator (bus/arbitrator/core.py and its parts), without threads:
 * pump() is the dispatch loop's body (host-link bytes, CAN frames, timers) and runs while a
 * request waits; arb_step() is the main loop's work (set-ups, departures, start-up and the
 * duty cycle), which issues requests.
 *
 * - Listening: for LISTEN_MS (2.2 arbitrator beacon intervals, as claim.py) from when the CAN
 *   side is on the bus (port_can_ready) nothing is written; one beacon heard by then extends
 *   it by two intervals, for the second.  An
 *   arbitrator is heard by its beacons: two mode-1 Device Beacons (node 0) within three
 *   intervals (reference §5).  Heard: no writes at all (no bind answers, no beacons), the host
 *   link serves read-only; the bus is taken back (a fresh start) RECLAIM_MS after the other's
 *   last beacon.  Not heard: Reset Device to node 0 (every device binds again) and a mode-1
 *   Device Beacon every ARB_BEACON_MS from then on.
 * - A device is gone after 3 missed beacon intervals plus half a one (reference §1 Decision);
 *   it stays in the tables, not present, with its links (dead links); its node IDs go back to
 *   the pool and the inputs it fed stop listening.
 * - A present device asking to bind again rebooted: it is set up again and its links re-made
 *   (PDCP Studio also tells a twin with the same VID/PID/serial from a reboot; not here).
 * - A device beaconing on a node ID nobody here gave (an earlier arbitrator's) gets a Reset
 *   Device, at most once a second, and binds again.
 */
#include <string.h>
#include "arb.h"
#include "port.h"

uint8_t g_may_write, g_other_heard, g_startup_done;
uint16_t g_changes;

static uint32_t listen_until, next_beacon, last_bind, last_change, started;
static uint32_t other_beacons[2];
static uint8_t duty_needed, resync[(MAX_DEVICES + 7) / 8];
static uint32_t foreign_reset_at[8];
static uint8_t foreign_reset_id[8];

static void note_change(int duty)
{
    last_change = port_millis();
    if (duty) duty_needed = 1;
}

static uint8_t can_up;

void arb_init(void)
{
    started = port_millis();
    last_bind = last_change = started;
    g_may_write = 0;
}

static void send_beacon(void)
{
    uint8_t b = 0x0A;
    can_send((uint16_t)(1 << 8), &b, 1);   /* priority 0, mode 1, node 0 */
}

static void claim_bus(void)
{
    uint8_t r = 0x0B;
    g_may_write = 1;
    can_send((uint16_t)((1 << 9) | (1 << 8)), &r, 1);   /* Reset Device, node 0: all bind again */
    next_beacon = port_millis();
    last_bind = port_millis();
}

/* Forget the bus (a restart without a power cycle): every device binds again. */
void arb_reset_all(void)
{
    for (int i = 0; i < MAX_DEVICES; i++) memset(&g_dev[i], 0, sizeof g_dev[i]);
    for (int c = 0; c < MAX_CHANNELS; c++) g_ch[c].used = 0;
    g_nlinks = 0;
    nodes_clear();
    g_startup_done = 0;
    duty_needed = 0;
    started = port_millis();
    if (g_may_write) claim_bus();
}

static void other_beacon(uint32_t now)
{
#ifdef PDCP_DEBUG
    { char t[40]; fmt_text(t, sizeof t, "beacon heard at %u", (unsigned)now); port_log(t); }
#endif
    uint32_t first = other_beacons[1];
    other_beacons[0] = other_beacons[1];
    other_beacons[1] = now | 1;
    if (first && now - first <= 3u * ARB_BEACON_MS && !g_other_heard) {
        g_other_heard = 1;
        g_may_write = 0;
        static const char t[] = "another arbitrator was heard on the bus (its beacons): this "
                                "one stops writing and serves its host link read-only";
        uint8_t msg[120];
        msg[0] = 0x45;
        memcpy(msg + 1, t, sizeof t - 1);
        hl_event(msg, (int)sizeof t);
        port_log("another arbitrator heard: not writing");
    }
}

static void claim_tick(uint32_t now)
{
    if (!can_up) {              /* listening starts when the CAN side is on the bus */
        if (!port_can_ready()) return;
        can_up = 1;
        listen_until = now + LISTEN_MS;
        started = last_bind = last_change = now;
    }
    if (g_other_heard) {
        if ((int32_t)(now - other_beacons[1]) > (int32_t)RECLAIM_MS) {
            g_other_heard = 0;
            other_beacons[0] = other_beacons[1] = 0;
            port_log("the other arbitrator's beacons are gone: taking the bus back");
            g_may_write = 1;
            arb_reset_all();
        }
        return;
    }
    if (!g_may_write) {
        static uint8_t extended;
        if ((int32_t)(now - listen_until) >= 0 && other_beacons[1] && !extended) {
            /* one beacon heard while listening: wait for its second (a late beacon) */
            extended = 1;
            listen_until = now + 2 * ARB_BEACON_MS;
            return;
        }
        if ((int32_t)(now - listen_until) >= 0) {
            port_log("no other bus arbitrator heard: arbitrating");
            claim_bus();
        }
        return;
    }
    if ((int32_t)(now - next_beacon) >= 0) {
        send_beacon();
        next_beacon = now + ARB_BEACON_MS;
    }
}

/* -- frames ------------------------------------------------------------------------------ */
static void on_bind(const uint8_t *d, uint8_t asked, uint32_t now)
{
    dev_key_t k = { get16(d + 1), get16(d + 3), get16(d + 5) };
    uint8_t grant = 0;
    last_bind = now;
    if (!g_may_write) return;            /* listening: the device asks again */
    int dev = dev_add(&k);
    if (dev < 0) return;
    device_t *dv = &g_dev[dev];
    int r = nodes_bind(&k, asked, now, &grant);
    if (!r) {
        if (!nodes_exhausted_reported(dev)) {
            char t[100];
            fmt_text(t, sizeof t, "device %k cannot bind: all 254 node IDs are in use by "
                     "devices and output channels", &k);
            hl_event_error(4, t);
        }
        return;
    }
    uint8_t f[8] = { 0x81, grant };
    memcpy(f + 2, d + 1, 6);
    can_send((uint16_t)((1 << 9) | (1 << 8) | asked), f, 8);
    if (r == 1) {
        if (dv->node_id && dv->node_id != grant) nodes_release_device(dev);
        dv->node_id = grant;
        dv->last_seen = now;
        dv->set_up = 0;
        dv->needs_setup = 1;
    }
}

static void reset_foreign(uint8_t node, uint32_t now)
{
    int slot = node % 8;
    if (foreign_reset_id[slot] == node && now - foreign_reset_at[slot] < UNKNOWN_RESET_MS) return;
    foreign_reset_id[slot] = node;
    foreign_reset_at[slot] = now;
    uint8_t r = 0x0B;
    can_send_arb(node, &r, 1);
}

/* Returns 1 when the frame answered the request waiting (pump() then stops reading: the
 * frames after it, such as bulk packets, are for the next step of that request). */
static int on_frame(uint16_t id, const uint8_t *d, uint8_t len, uint32_t now)
{
    uint8_t mode = (uint8_t)(id >> 8 & 1), node = (uint8_t)id, prio = (uint8_t)(id >> 9);
#if MONITOR
    mon_frame(id, d, len);
#endif
    if (mode) {
        if (node == 0 && len == 1 && d[0] == 0x0A) other_beacon(now);
        return 0;   /* any other mode-1 frame: a stray frame, never a reason to leave */
    }
    if (prio == 3) {
        if (len >= 7 && d[0] == 0x01) on_bind(d, node, now);
        return 0;
    }
    if (req_on_frame(id, d, len)) {
        int dev = nodes_owner_dev(node);
        if (dev >= 0) g_dev[dev].last_seen = now;
        return 1;
    }
    int dev = nodes_owner_dev(node);
    if (dev >= 0) {
        g_dev[dev].last_seen = now;
        if (len >= 2 && d[0] == 0x0F && g_may_write) {
            uint8_t r[3] = { 0x8F, 1, d[1] };
            can_send_arb(node, r, 3);
            if (g_dev[dev].set_up) resync[dev / 8] |= (uint8_t)(1 << (dev % 8));
        }
        return 0;
    }
    if (nodes_is_channel(node) || !node) return 0;   /* channel data */
    nodes_hear_foreign(node, now);
    if (len == 1 && d[0] == 0x0A && g_may_write) reset_foreign(node, now);
    return 0;
}

static int pumping;

void pump(void)
{
    uint8_t buf[64];
    int n;
    uint16_t id;
    uint8_t d[8], len;
    if (pumping) return;
    pumping = 1;
    while ((n = port_host_read(buf, sizeof buf)) > 0) hl_rx(buf, n);
    for (int k = 0; k < 32 && port_can_read(&id, d, &len); k++)
        if (on_frame(id, d, len, port_millis())) break;
    uint32_t now = port_millis();
    claim_tick(now);
    nodes_expire(now);
    hl_poll();
    pumping = 0;
}

/* -- set-up (reference §1 steps 1–6) --------------------------------------------------- */
static uint32_t bitmap(const uint8_t *v, uint16_t n)
{
    uint32_t m = 0;
    for (uint16_t b = 0; b < n && b < 4; b++)
        for (int j = 7; j >= 0; j--)
            if (v[b] & (1 << j)) m |= 1u << (b * 8 + (7 - j));
    return m;
}

typedef struct {
    uint8_t dir;
    uint16_t type, profile, term;
    uint32_t req, des;
    source_t src;
    uint8_t desc_len;
    char desc[CH_DESC_MAX];
} read_ch_t;

static read_ch_t rd[MAX_CH_PER_DEVICE];

static int get_p(uint8_t node, uint8_t param, uint8_t chan, uint8_t *v, uint16_t *n)
{
    int r = req_get(node, param, chan, v, 64, n);
    if (r == REQ_REFUSED) { *n = 0; return REQ_OK; }   /* a parameter it does not have */
    return r;
}

static void setup_failed(int dev, const char *what)
{
    device_t *d = &g_dev[dev];
    char t[120];
    d->setup_failures++;
    d->setup_failed_at = port_millis();
    int again = d->setup_failures < SETUP_ATTEMPTS;
    fmt_text(t, sizeof t, "set-up of device %k (node %u) failed: %s%s", &d->key, d->node_id,
             what, again ? "; resetting it to try again" : "");
    hl_event_error(5, t);
    port_log(t);
    d->needs_setup = 0;
    if (again) {
        uint8_t r = 0x0B;
        can_send_arb(d->node_id, &r, 1);
    }
}

static void do_setup(int dev)
{
    static uint8_t v[64];
    uint16_t n;
    device_t *d = &g_dev[dev];
    uint8_t node = d->node_id;
    device_t got;
    memset(&got, 0, sizeof got);
    d->needs_setup = 0;
    static const uint8_t dev_params[] = { 1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12 };
    for (unsigned i = 0; i < sizeof dev_params; i++) {
        uint8_t p = dev_params[i];
        if (get_p(node, p, 0, v, &n) != REQ_OK) { setup_failed(dev, "no answer to a device parameter"); return; }
        if (d->node_id != node) return;      /* it bound again meanwhile */
        switch (p) {
        case 1: if (n >= 4 && (get16(v) != d->key.vid || get16(v + 2) != d->key.pid)) {
                    char t[80];
                    fmt_text(t, sizeof t, "device %k after binding: node %u answered as %u/%u",
                             &d->key, node, get16(v), get16(v + 2));
                    hl_event_error(5, t);
                } break;
        case 3: if (n >= 4) got.ean_lo = get32(v); break;
        case 4: if (n >= 4) got.ean_hi = get32(v); break;
        case 5: if (n >= 4) { got.fw = get16(v); got.hw = get16(v + 2); } break;
        case 6: if (n >= 4) { got.dtype = get16(v); got.dprofile = get16(v + 2); } break;
        case 7: {
            while (n && v[n - 1] == 0) n--;
            got.desc_len = (uint8_t)(n > DESC_MAX ? DESC_MAX : n);
            memcpy(got.desc, v, got.desc_len);
        } break;
        case 9: got.nch = n ? v[0] : 0; break;
        case 10: got.beacon_ms = n >= 2 ? get16(v) : 0; break;
        case 11: got.ack_ms = n >= 2 ? get16(v) : 0; break;
        case 12: got.bind_ms = n >= 2 ? get16(v) : 0; break;
        default: break;
        }
    }
    if (got.nch > MAX_CH_PER_DEVICE - 1) got.nch = MAX_CH_PER_DEVICE - 1;
    static const uint8_t in_params[] = { 1, 2, 5, 6, 8, 9, 10, 11 };
    static const uint8_t out_params[] = { 1, 2, 9, 10 };
    for (uint8_t c = 1; c <= got.nch; c++) {
        read_ch_t *ch = &rd[c];
        memset(ch, 0, sizeof *ch);
        ch->src.vid = ch->src.pid = ch->src.serial = 0xFFFF; ch->src.index = 0xFF;
        if (get_p(node, 3, c, v, &n) != REQ_OK) { setup_failed(dev, "no answer to Transfer Type"); return; }
        ch->dir = n ? v[0] : 0;
        if (ch->dir != DIR_IN && ch->dir != DIR_OUT) { ch->dir = 0; continue; }
        const uint8_t *ps = ch->dir == DIR_IN ? in_params : out_params;
        unsigned np = ch->dir == DIR_IN ? sizeof in_params : sizeof out_params;
        for (unsigned i = 0; i < np; i++) {
            if (get_p(node, ps[i], c, v, &n) != REQ_OK) {
                char t[48];
                fmt_text(t, sizeof t, "no answer to parameter %u of channel %u", ps[i], c);
                setup_failed(dev, t);
                return;
            }
            if (d->node_id != node) return;
            switch (ps[i]) {
            case 1: if (n >= 4) { ch->type = get16(v); ch->profile = get16(v + 2); } break;
            case 2: while (n && v[n - 1] == 0) n--;
                    ch->desc_len = (uint8_t)(n > CH_DESC_MAX ? CH_DESC_MAX : n);
                    memcpy(ch->desc, v, ch->desc_len); break;
            case 5: if (n >= 4) { ch->src.vid = get16(v); ch->src.pid = get16(v + 2); } break;
            case 6: if (n >= 3) { ch->src.serial = get16(v); ch->src.index = v[2]; } break;
            case 8: if (n >= 4) { ch->src.type = get16(v); ch->src.profile = get16(v + 2); } break;
            case 9: ch->req = bitmap(v, n); break;
            case 10: ch->des = bitmap(v, n); break;
            case 11: if (n >= 2) ch->term = get16(v); break;
            default: break;
            }
        }
    }
    /* step 4: node IDs for the outputs, written to Channel Node Id */
    for (uint8_t c = 1; c <= got.nch; c++) {
        if (rd[c].dir != DIR_OUT) continue;
        int cid = nodes_take_output(dev, c);
        if (!cid) {
            if (!nodes_exhausted_reported(dev)) {
                char t[110];
                fmt_text(t, sizeof t, "output %k.%u gets no node ID and cannot be linked: all "
                         "254 node IDs are in use", &d->key, c);
                hl_event_error(4, t);
            }
            continue;
        }
        uint8_t idv = (uint8_t)cid;
        if (req_set(node, 5, c, &idv, 1) != REQ_OK) { setup_failed(dev, "Channel Node Id"); return; }
    }
    /* install the device and its channels */
    int joined = !d->present;
    d->fw = got.fw; d->hw = got.hw; d->dtype = got.dtype; d->dprofile = got.dprofile;
    d->ean_lo = got.ean_lo; d->ean_hi = got.ean_hi; d->nch = got.nch;
    d->beacon_ms = got.beacon_ms; d->ack_ms = got.ack_ms; d->bind_ms = got.bind_ms;
    d->desc_len = got.desc_len; memcpy(d->desc, got.desc, got.desc_len);
    uint32_t inputs = 0;
    for (uint8_t c = 1; c <= got.nch; c++) if (rd[c].dir == DIR_IN) inputs |= 1u << c;
    for (int c = 0; c < MAX_CHANNELS; c++)
        if (g_ch[c].used && g_ch[c].dev == dev && (g_ch[c].index > got.nch || !rd[g_ch[c].index].dir))
            g_ch[c].used = 0;
    for (uint8_t c = 1; c <= got.nch; c++) {
        if (!rd[c].dir) continue;
        int s = ch_of(dev, c);
        if (s < 0)
            for (int i = 0; i < MAX_CHANNELS; i++) if (!g_ch[i].used) { s = i; break; }
        if (s < 0) { hl_event_error(5, "the channel table is full"); break; }
        channel_t *ch = &g_ch[s];
        memset(ch, 0, sizeof *ch);
        ch->used = 1; ch->dev = (uint8_t)dev; ch->index = c; ch->dir = rd[c].dir;
        ch->type = rd[c].type; ch->profile = rd[c].profile; ch->term_profile = rd[c].term;
        ch->req = rd[c].req & inputs; ch->des = rd[c].des & inputs;
        ch->src = rd[c].src;
        ch->desc_len = rd[c].desc_len; memcpy(ch->desc, rd[c].desc, rd[c].desc_len);
    }
    /* links that no longer fit (a channel changed direction) go */
    for (int l = (int)g_nlinks - 1; l >= 0; l--) {
        int o = ch_find(&g_links[l].out), i = ch_find(&g_links[l].in);
        if ((o >= 0 && g_ch[o].dir != DIR_OUT) || (i >= 0 && g_ch[i].dir != DIR_IN) ||
            ((ref_on(&g_links[l].out, &d->key) && o < 0) || (ref_on(&g_links[l].in, &d->key) && i < 0)))
            link_del(l);
    }
    d->present = 1; d->in_system = 1; d->set_up = 1; d->setup_failures = 0;
    d->last_seen = port_millis();
    note_change(joined);
    for (uint16_t l = 0; l < g_nlinks; l++) {
        link_t lk = g_links[l];
        if ((ref_on(&lk.out, &d->key) || ref_on(&lk.in, &d->key)) &&
            ref_present(&lk.out, DIR_OUT) && ref_present(&lk.in, DIR_IN))
            arb_wire_add(&lk);
    }
    if (joined) {
        hl_event_device(0x41, dev);
        char t[64];
        fmt_text(t, sizeof t, "device %k joined (node %u, %u channels)", &d->key, node, d->nch);
        port_log(t);
    }
}

/* -- departures ------------------------------------------------------------------------ */
static void leave(int dev)
{
    device_t *d = &g_dev[dev];
    int was = d->present;
    /* why, measured before the links below take the bus's time (§5.7) */
    uint32_t silent = port_millis() - d->last_seen;
    uint16_t interval = d->set_up && d->beacon_ms ? d->beacon_ms : UNREAD_BEACON_MS;
    d->present = 0;
    d->set_up = 0;
    d->needs_setup = 0;
    nodes_release_device(dev);
    if (!was) return;
    note_change(1);
    /* inputs fed by its outputs stop listening (their node IDs may be reused) */
    for (uint16_t l = 0; l < g_nlinks; l++) {
        link_t lk = g_links[l];
        if (!ref_on(&lk.out, &d->key)) continue;
        int in = ch_find(&lk.in);
        if (in < 0 || !g_dev[g_ch[in].dev].present) continue;
        uint8_t node = g_dev[g_ch[in].dev].node_id, off = 0, ids[2] = { 0, 0 };
        if (req_set(node, 4, lk.in.index, &off, 1) == REQ_OK &&
            req_set(node, 7, lk.in.index, ids, 2) == REQ_OK)
            g_ch[in].enabled = 0;
    }
    char t[48];
    fmt_text(t, sizeof t, "no beacon for %u ms", (unsigned)(silent > 0xFFFFu ? 0xFFFFu : silent));
    hl_event_left(dev, silent, interval, t);
    fmt_text(t, sizeof t, "device %k left", &d->key);
    port_log(t);
}

/* -- links on the wire (bus/arbitrator/links.py) ----------------------------------------- */
static int wr(uint8_t node, uint8_t param, uint8_t chan, const uint8_t *v, uint16_t n)
{
    return req_set(node, param, chan, v, n);
}

int arb_wire_add(const link_t *l)
{
    int o = ch_find(&l->out), i = ch_find(&l->in);
    if (o < 0 || i < 0) return REQ_ABSENT;
    uint8_t in_node = g_dev[g_ch[i].dev].node_id, out_node = g_dev[g_ch[o].dev].node_id;
    uint8_t out_id = node_output_id(&l->out);
    if (!in_node || !out_node || !out_id) return REQ_ABSENT;
    channel_t *ic = &g_ch[i], *oc = &g_ch[o];
    source_t want = { l->out.vid, l->out.pid, l->out.serial, l->out.index, oc->type, oc->profile };
    uint8_t v[4];
    int r;
    v[0] = out_node; v[1] = out_id;
    if ((r = wr(in_node, 7, l->in.index, v, 2))) return r;
    if (want.vid != ic->src.vid || want.pid != ic->src.pid) {
        put16(v, want.vid); put16(v + 2, want.pid);
        if ((r = wr(in_node, 5, l->in.index, v, 4))) return r;
    }
    if (want.serial != ic->src.serial || want.index != ic->src.index) {
        put16(v, want.serial); v[2] = want.index;
        if ((r = wr(in_node, 6, l->in.index, v, 3))) return r;
    }
    if (want.type != ic->src.type || want.profile != ic->src.profile) {
        put16(v, want.type); put16(v + 2, want.profile);
        if ((r = wr(in_node, 8, l->in.index, v, 4))) return r;
    }
    ic->src = want;
    v[0] = 1;
    if ((r = wr(in_node, 4, l->in.index, v, 1))) return r;
    ic->enabled = 1;
    if ((r = wr(out_node, 4, l->out.index, v, 1))) return r;
    oc->enabled = 1;
    return REQ_OK;
}

/* After the tables dropped l: clear the input unless it has another source, stop the output
 * unless it still feeds a present input. */
int arb_wire_remove(const link_t *l)
{
    int o = ch_find(&l->out), i = ch_find(&l->in), r = REQ_OK;
    uint8_t v[4];
    if (i >= 0 && g_dev[g_ch[i].dev].present && link_source_of(&l->in, 0) < 0) {
        uint8_t node = g_dev[g_ch[i].dev].node_id;
        v[0] = 0;
        if ((r = wr(node, 4, l->in.index, v, 1))) return r;
        v[0] = v[1] = 0;
        if ((r = wr(node, 7, l->in.index, v, 2))) return r;
        v[0] = v[1] = v[2] = v[3] = 0xFF;
        if ((r = wr(node, 5, l->in.index, v, 4))) return r;
        if ((r = wr(node, 6, l->in.index, v, 3))) return r;
        v[0] = v[1] = v[2] = v[3] = 0;
        if ((r = wr(node, 8, l->in.index, v, 4))) return r;
        g_ch[i].enabled = 0;
        g_ch[i].src.vid = g_ch[i].src.pid = g_ch[i].src.serial = 0xFFFF;
        g_ch[i].src.index = 0xFF; g_ch[i].src.type = g_ch[i].src.profile = 0;
    }
    if (o >= 0 && g_dev[g_ch[o].dev].present) {
        int feeds = 0;
        for (uint16_t k = 0; k < g_nlinks && !feeds; k++)
            feeds = !ref_cmp(&g_links[k].out, &l->out) && ref_present(&g_links[k].in, DIR_IN);
        if (!feeds) {
            v[0] = 0;
            if ((r = wr(g_dev[g_ch[o].dev].node_id, 4, l->out.index, v, 1))) return r;
            g_ch[o].enabled = 0;
        }
    }
    return r;
}

static int status_of(int r)
{
    return r == REQ_REFUSED ? 0x07 : r == REQ_TIMEOUT ? 0x08 : r == REQ_NOWRITE ? 0x12 : 0x06;
}

int arb_add_link(const link_t *l, char *why, int room)
{
    int o = ch_find(&l->out), i = ch_find(&l->in);
    if (!g_may_write) { fmt_text(why, room, "another arbitrator is on the bus: no writes"); return 0x12; }
    if (o < 0 || g_ch[o].dir != DIR_OUT) { fmt_text(why, room, "%r is not an output channel", &l->out); return 0x0A; }
    if (i < 0 || g_ch[i].dir != DIR_IN) { fmt_text(why, room, "%r is not an input channel", &l->in); return 0x0A; }
    if (link_find(l) >= 0) return 0;
    if (!ch_present(o) || !ch_present(i)) { fmt_text(why, room, "link: an end is not on the bus"); return 0x0A; }
    for (uint16_t k = 0; k < g_nlinks; k++) {
        if (ref_cmp(&g_links[k].in, &l->in)) continue;
        if (ref_present(&g_links[k].out, DIR_OUT)) {
            fmt_text(why, room, "input %r already has source %r", &l->in, &g_links[k].out);
            return 0x0A;
        }
    }
    for (int k = (int)g_nlinks - 1; k >= 0; k--) {      /* dead links into the input go */
        if (ref_cmp(&g_links[k].in, &l->in)) continue;
        link_t dead = g_links[k];
        link_del(k);
        arb_wire_remove(&dead);
        hl_event_link(0x44, &dead);
    }
    int r = arb_wire_add(l);
    if (r) { fmt_text(why, room, "writing the link failed"); return status_of(r); }
    if (link_add(l)) { fmt_text(why, room, "the link table is full"); return 0x0C; }
    hl_event_link(0x43, l);
    return 0;
}

int arb_remove_link(const link_t *l, char *why, int room)
{
    int k = link_find(l);
    if (!g_may_write) { fmt_text(why, room, "another arbitrator is on the bus: no writes"); return 0x12; }
    if (k < 0) { fmt_text(why, room, "link %r -> %r is not in the system", &l->out, &l->in); return 0x0A; }
    link_del(k);
    int r = arb_wire_remove(l);
    hl_event_link(0x44, l);
    if (r) { fmt_text(why, room, "clearing the link failed"); return status_of(r); }
    return 0;
}

/* -- parameters ------------------------------------------------------------------------ */
int arb_managed(int dev, uint8_t param, uint8_t chan)
{
    if (!chan) return param == 8;
    int c = ch_of(dev, chan);
    if (c < 0) return 0;
    return (g_ch[c].dir == DIR_OUT && param == 5) || (g_ch[c].dir == DIR_IN && param == 7);
}

static void learn(int dev, uint8_t param, uint8_t chan, const uint8_t *v, uint16_t n)
{
    device_t *d = &g_dev[dev];
    if (!chan) {
        if (param == 10 && n >= 2) d->beacon_ms = get16(v);
        else if (param == 11 && n >= 2) d->ack_ms = get16(v);
        else if (param == 12 && n >= 2) d->bind_ms = get16(v);
        return;
    }
    int c = ch_of(dev, chan);
    if (c < 0) return;
    channel_t *ch = &g_ch[c];
    if (param == 4 && n >= 1) ch->enabled = v[0] != 0;
    else if (param == 1 && n >= 4) { ch->type = get16(v); ch->profile = get16(v + 2); }
    else if (ch->dir == DIR_IN && param == 11 && n >= 2) ch->term_profile = get16(v);
    else if (ch->dir == DIR_IN && param == 5 && n >= 4) { ch->src.vid = get16(v); ch->src.pid = get16(v + 2); }
    else if (ch->dir == DIR_IN && param == 6 && n >= 3) { ch->src.serial = get16(v); ch->src.index = v[2]; }
    else if (ch->dir == DIR_IN && param == 8 && n >= 4) { ch->src.type = get16(v); ch->src.profile = get16(v + 2); }
}

int arb_get_param(int dev, uint8_t param, uint8_t chan, uint8_t *v, uint16_t room, uint16_t *len)
{
    int r = req_get(g_dev[dev].node_id, param, chan, v, room, len);
    if (!r) learn(dev, param, chan, v, *len);
    return r;
}

int arb_set_param(int dev, uint8_t param, uint8_t chan, const uint8_t *v, uint16_t len)
{
    int r = req_set(g_dev[dev].node_id, param, chan, v, len);
    if (!r) learn(dev, param, chan, v, len);
    return r;
}

/* -- the motion interlock (reference §5) ------------------------------------------------- */
int arb_hold(const dev_key_t *keys, int n, int *refused)
{
    uint8_t ms[2];
    put16(ms, INTERLOCK_MS);
    for (int i = 0; i < n; i++) {
        int dev = dev_find(&keys[i]);
        int r = dev < 0 || !g_dev[dev].present ? REQ_ABSENT
                : req_simple(g_dev[dev].node_id, 0x08, ms, 2);
        if (r) { *refused = i; arb_release(keys, i); return r; }
    }
    return REQ_OK;
}

void arb_release(const dev_key_t *keys, int n)
{
    for (int i = 0; i < n; i++) {
        int dev = dev_find(&keys[i]);
        if (dev >= 0 && g_dev[dev].present) req_simple(g_dev[dev].node_id, 0x09, 0, 0);
    }
}

/* -- the main loop's work ---------------------------------------------------------------- */
static int setups_pending(void)
{
    for (int i = 0; i < MAX_DEVICES; i++)
        if (g_dev[i].used && g_dev[i].node_id && !g_dev[i].set_up &&
            (g_dev[i].needs_setup || g_dev[i].setup_failures < SETUP_ATTEMPTS))
            return 1;
    return 0;
}

int arb_settled(void)
{
    return g_startup_done && !duty_needed && !setups_pending();
}

void arb_step(void)
{
    uint32_t now = port_millis();
    for (int i = 0; i < MAX_DEVICES; i++) {
        device_t *d = &g_dev[i];
        if (!d->used || !d->node_id) continue;
        uint32_t interval = d->set_up && d->beacon_ms ? d->beacon_ms : UNREAD_BEACON_MS;
        uint32_t silence = interval * MISSED_BEACONS_X2 / 2;
#if PRESENCE_MIN_MS
        if (silence < PRESENCE_MIN_MS) silence = PRESENCE_MIN_MS;
#endif
        if (now - d->last_seen > silence) {
            leave(i);
            return;
        }
    }
    if (!g_may_write) return;
    for (int i = 0; i < MAX_DEVICES; i++) {
        device_t *d = &g_dev[i];
        /* every attempt failed, yet it beacons on: try once more now and then (a bus that was
         * too slow for a while must not leave a device unusable until it is replugged) */
        if (d->used && d->node_id && !d->set_up && !d->needs_setup &&
            d->setup_failures >= SETUP_ATTEMPTS && now - d->setup_failed_at >= SETUP_RETRY_MS) {
            d->setup_failures = SETUP_ATTEMPTS - 1;
            d->needs_setup = 1;
        }
        if (d->used && d->node_id && d->needs_setup) {
            do_setup(i);
            return;
        }
    }
    for (int i = 0; i < MAX_DEVICES; i++) {
        if (!(resync[i / 8] & (1 << (i % 8)))) continue;
        resync[i / 8] &= (uint8_t)~(1 << (i % 8));
        for (uint16_t l = 0; l < g_nlinks; l++) {
            link_t lk = g_links[l];
            if (ref_on(&lk.in, &g_dev[i].key) && ref_present(&lk.out, DIR_OUT) &&
                ref_present(&lk.in, DIR_IN))
                arb_wire_add(&lk);
        }
    }
    int pending = setups_pending();
    if (!g_startup_done) {
        int quiet = now - last_bind >= STARTUP_QUIET_MS && !pending;
        if (quiet || (now - started >= STARTUP_MAX_WAIT_MS && !pending)) {
            duty_needed = 0;
            profile_startup();
            g_startup_done = 1;
            profile_note_present();
        }
        return;
    }
    if (duty_needed && !pending && now - last_change >= DUTY_QUIET_MS) {
        duty_needed = 0;
        profile_duty_cycle();
        profile_note_present();
    }
}
