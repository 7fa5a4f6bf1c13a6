/* Host link 2, the arbitrator's side (docs/host-link.md): frames, the link machine, requests.
 *
 * Frames: COBS( kind | seq | len | payload | CRC-16 BE ) 0x00.  Stop-and-wait per direction:
 * one DATA frame in flight (resent on NAK or after ACK_TIMEOUT_MS, given up after
 * MAX_ATTEMPTS sends, and with it the PC: it must greet again), ACK/NAK written at once.
 * A NAK naming a frame this end will not send again (one given up while the line was cut) is
 * answered with RESET, so the PC renumbers instead of waiting for ever (§3.4); a RESET from the
 * PC drops the frame in flight and the queue (dropped events count as lost) and keeps the
 * session (§3.3).  Requests arrive in a one-message mailbox; those answered from the tables
 * and the memory (no CAN traffic) are answered inside pump(), the others by hl_service() from
 * the main loop.  Events wait in a queue of EVENT_QUEUE messages of at most EVENT_MAX bytes
 * each (texts are cut to fit at a UTF-8 character boundary; a TERMINALS_UNCONNECTED whose
 * references do not fit is counted as lost, §5.7); one that does not fit is counted and
 * EVENTS_LOST is sent when there is room again.
 *
 * Requests served: HELLO, STATUS, LIST_DEVICES, GET_DEVICE, GET_CHANNELS, LIST_LINKS,
 * GET_PARAM, SET_PARAM, ADD_LINK, REMOVE_LINK, SUSPEND, RELEASE, RESET_DEVICE, CONFIG_INFO,
 * CONFIG_READ, CONFIG_WRITE_BEGIN/_CHUNK/_COMMIT, TRANSACT_BEGIN/_CHUNK/_RUN, RESULT_READ,
 * GET_POLICY, MONITOR (when built with the monitor, src/monitor.c; else UNSUPPORTED and
 * capability bit 0 not declared).  Any other code, 0x40-0xFF included, is answered
 * UNKNOWN_REQUEST.  A version-1 request without a body (PING) is answered in version 1 with a
 * failure reply saying why (§4: a 6-byte window on the raw bytes).
 */
#include <string.h>
#include "arb.h"
#include "port.h"

#define ACK_TIMEOUT_MS 250
#define MAX_ATTEMPTS 8
#define MAX_PAYLOAD 255
#define MAX_RAW (3 + MAX_PAYLOAD + 2)
#define MAX_ENC (MAX_RAW + 2)
#define CHUNK 240
#define BODY_ROOM 253                 /* a reply's body after its status byte */
#define MAX_CHANGE 16384u
#ifdef __AVR__
#  define EVENT_QUEUE 8
#  define EVENT_MAX 40
#else
#  define EVENT_QUEUE 16
#  define EVENT_MAX 64
#endif
/* transactions, policy; parameters longer than a frame when the value buffer holds more
 * than one (bit 3, §4); and the monitor when built */
#define CAPABILITIES (0x0006 | (VALUE_MAX > CHUNK ? 8 : 0) | (MONITOR ? 1 : 0))

enum { ST_OK = 0, ST_UNKNOWN_REQUEST, ST_BAD_LENGTH, ST_NOT_GREETED, ST_VERSION,
       ST_UNKNOWN_DEVICE, ST_DEVICE_ABSENT, ST_DEVICE_REFUSED, ST_DEVICE_TIMEOUT, ST_MANAGED,
       ST_BAD_LINK, ST_BAD_OFFSET, ST_TOO_LARGE, ST_CHECKSUM, ST_BAD_CONFIGURATION,
       ST_NO_TRANSFER, ST_BUSY, ST_INTERLOCK, ST_OTHER_ARBITRATOR, ST_STORAGE,
       ST_UNSUPPORTED, ST_INTERNAL = 0x1F };

static uint8_t rx[MAX_ENC];
static uint16_t rx_len;
static uint8_t rx_over;
static uint8_t tx_seq, rx_expected;
/* The CRC of the last DATA frame delivered since a RESET (last_ok: there is one): a repeat is
 * the same frame, so one numbered like it with another CRC is the PC numbering anew (§3.2). */
static uint16_t last_crc;
static uint8_t last_ok;

static uint8_t inflight[MAX_ENC + 1];
static uint16_t inflight_len;
static uint8_t inflight_seq, attempts;
static uint8_t inflight_payload;      /* the message code of the frame in flight */
static uint32_t deadline;

static uint8_t mailbox[MAX_PAYLOAD];
static uint16_t mailbox_len;          /* 0: empty */

static uint8_t reply[MAX_PAYLOAD];
static uint16_t reply_len;            /* 0: none waiting */

static uint8_t events[EVENT_QUEUE][EVENT_MAX];
static uint8_t event_len[EVENT_QUEUE];
static uint8_t ev_head, ev_count, lost_pending;
static uint16_t events_lost;

static uint8_t greeted;
static uint8_t handling;        /* a request is being answered from the main loop */
static uint8_t value[VALUE_MAX];
static uint16_t value_len;
static uint8_t value_addr[8], value_valid;
static uint8_t set_addr[8], set_active;
static uint16_t set_total, set_have;
static struct { uint8_t active; uint16_t total, crc, have; } cfgw, chg;
static uint8_t result_valid;
static uint16_t result_len, result_crc;

int hl_greeted(void) { return greeted; }

/* -- frames ------------------------------------------------------------------------------ */
static uint16_t cobs_encode(const uint8_t *in, uint16_t n, uint8_t *out)
{
    uint16_t o = 1, code_at = 0;
    uint8_t code = 1;
    for (uint16_t i = 0; i < n; i++) {
        if (in[i] == 0) {
            out[code_at] = code; code_at = o++; code = 1;
        } else {
            out[o++] = in[i]; code++;
            if (code == 0xFF) { out[code_at] = code; code_at = o++; code = 1; }
        }
    }
    out[code_at] = code;
    return o;
}

static int cobs_decode(uint8_t *buf, uint16_t n, uint16_t *out_len)
{
    uint16_t i = 0, o = 0;
    while (i < n) {
        uint8_t code = buf[i];
        if (!code || i + code > n) return -1;
        for (uint8_t k = 1; k < code; k++) buf[o++] = buf[i + k];
        i = (uint16_t)(i + code);
        if (code != 0xFF && i < n) buf[o++] = 0;
    }
    *out_len = o;
    return 0;
}

static uint16_t frame(uint8_t kind, uint8_t seq, const uint8_t *payload, uint16_t len, uint8_t *out)
{
    static uint8_t raw[MAX_RAW];
    raw[0] = kind; raw[1] = seq; raw[2] = (uint8_t)len;
    if (len) memcpy(raw + 3, payload, len);
    uint16_t c = crc16(raw, (size_t)(3 + len));
    raw[3 + len] = (uint8_t)(c >> 8); raw[4 + len] = (uint8_t)c;
    uint16_t n = cobs_encode(raw, (uint16_t)(len + 5), out);
    out[n++] = 0;
    return n;
}

static void control(uint8_t kind, uint8_t seq)
{
    uint8_t out[8];
    uint16_t n = frame(kind, seq, 0, 0, out);
    port_host_write(out, n);
}

static void transmit(void)
{
    attempts++;
    deadline = port_millis() + ACK_TIMEOUT_MS;
    port_host_write(inflight, inflight_len);
}

static void send_data(const uint8_t *msg, uint16_t len)
{
    inflight_seq = tx_seq++;
    inflight_payload = msg[0];
    inflight_len = frame(1, inflight_seq, msg, len, inflight);
    attempts = 0;
    transmit();
}

/* A frame was given up (the PC stopped acknowledging): the PC greets again.  A reply waiting
 * behind that frame stays: it answers a request the PC sent while greeted and waits for
 * (dropping it left the PC waiting out its whole reply timeout), as PDCP Studio's link keeps
 * what is queued behind a frame it gives up. */
static void forget_host(void)
{
#if MONITOR
    mon_stop();
#endif
    greeted = 0;
    ev_count = 0; lost_pending = 0;
    cfgw.active = chg.active = 0;
    set_active = 0;
}

/* An event a RESET drops is counted as lost (the monitor's are not: they are samples). */
static int is_counted_event(uint8_t code)
{
    return code >= 0x41 && code < 0x80 && code != 0x47 && code != 0x48;
}

static void pump_out(void)
{
    if (inflight_len) return;
    if (reply_len) {
        send_data(reply, reply_len);
        reply_len = 0;
    } else if (ev_count) {
        send_data(events[ev_head], event_len[ev_head]);
        ev_head = (uint8_t)((ev_head + 1) % EVENT_QUEUE);
        ev_count--;
    } else if (lost_pending && greeted) {
        uint8_t m[3] = { 0x49 };
        put16(m + 1, events_lost);
        lost_pending = 0;
        send_data(m, 3);
    }
#if MONITOR
    else if (greeted && !mailbox_len) {
        static uint8_t m[MAX_PAYLOAD];
        int n = mon_take(m);
        if (n) send_data(m, (uint16_t)n);
    }
#endif
}

static void on_frame(uint8_t *raw, uint16_t n)
{
    if (n < 5) { control(3, rx_expected); return; }
    uint16_t c = crc16(raw, (size_t)(n - 2));
    if (c != (uint16_t)(raw[n - 2] << 8 | raw[n - 1]) || raw[2] != n - 5 || !raw[0] || raw[0] > 4) {
        control(3, rx_expected);
        return;
    }
    uint8_t kind = raw[0], seq = raw[1];
    if (kind == 1) {
        if (seq == rx_expected) {
            control(2, seq);
            rx_expected++;
            last_crc = c;
            last_ok = 1;
            /* A request waiting while the PC sent another: the PC gave the first up (its reply
             * timed out), so the new one takes its place — unless the first is running. */
            if (raw[2] && (!mailbox_len || !handling)) {
                memcpy(mailbox, raw + 3, raw[2]);
                mailbox_len = raw[2];
            }
        } else if (seq == (uint8_t)(rx_expected - 1)) {
            if (last_ok && c != last_crc) control(4, 0);  /* not a repeat: "renumber, please" */
            else control(2, seq);
        } else {
            control(3, rx_expected);
        }
    } else if (kind == 2) {
        if (inflight_len && seq == inflight_seq) inflight_len = 0;
    } else if (kind == 3) {
        if (!inflight_len) {
            /* the PC waits for a frame given up (the line was cut): "renumber, please" */
            if (seq != tx_seq) control(4, 0);
            return;
        }
        if (seq == inflight_seq) { if (attempts < MAX_ATTEMPTS) transmit(); }
        else if (seq == (uint8_t)(inflight_seq + 1)) inflight_len = 0;
        else control(4, 0);
    } else if (kind == 4) {
        /* §3.3: drop the frame in flight and the queue, count the events among them as lost,
         * keep the session (greeted, transfers open) */
        uint8_t dropped = 0;
        if (inflight_len && is_counted_event(inflight_payload)) dropped++;
        for (uint8_t i = 0; i < ev_count; i++)
            if (is_counted_event(events[(ev_head + i) % EVENT_QUEUE][0])) dropped++;
        if (dropped && greeted) { events_lost = (uint16_t)(events_lost + dropped); lost_pending = 1; }
        tx_seq = rx_expected = 0;
        last_ok = 0;
        inflight_len = 0;
        reply_len = 0;
        ev_count = 0;
    }
    pump_out();
}

/* Version 1 (§4): A5 | id | length u16 LE | payload | CRC u16 LE over id, length, payload.
 * A request without a body (PING, 0x10) is seen in the last 6 bytes and answered with the
 * failure reply (id + 2) in version 1, whether greeted or not, as PDCP Studio's arbitrator does. */
static uint8_t v1win[6];

static void v1_sniff(uint8_t b)
{
    uint8_t out[4 + 80 + 2];
    memmove(v1win, v1win + 1, 5);
    v1win[5] = b;
    uint8_t id = v1win[1];
    if (v1win[0] != 0xA5 || v1win[2] || v1win[3] || id < 0x10 || id > 0x37 || (id - 0x10) % 3)
        return;
    if (crc16(v1win + 1, 3) != (uint16_t)(v1win[4] | v1win[5] << 8)) return;
    /* a format without '%': on the AVR it stays in flash */
    int k = fmt_text((char *)out + 4, 81, "this arbitrator speaks host-link version 2, not "
                     "version 1: update PDCP Studio");
    out[0] = 0xA5; out[1] = (uint8_t)(id + 2);
    put16(out + 2, (uint16_t)k);
    put16(out + 4 + k, crc16(out + 1, (size_t)(3 + k)));
    port_host_write(out, 4 + k + 2);
}

void hl_rx(const uint8_t *data, int len)
{
    for (int i = 0; i < len; i++) {
        uint8_t b = data[i];
        v1_sniff(b);
        if (b) {
            if (rx_len >= MAX_ENC) rx_over = 1;
            else if (!rx_over) rx[rx_len++] = b;
            continue;
        }
        if (rx_over) control(3, rx_expected);
        else if (rx_len) {
            uint16_t n;
            if (cobs_decode(rx, rx_len, &n)) control(3, rx_expected);
            else on_frame(rx, n);
        }
        rx_len = 0;
        rx_over = 0;
    }
}

/* -- events ------------------------------------------------------------------------------ */
/* Where an event's text starts (the events with a reason, §5.7); 0: no text. */
static int text_at(const uint8_t *msg, int len)
{
    switch (msg[0]) {
    case 0x42: return 11;   /* DEVICE_LEFT: key, silent ms, beacon interval ms, reason */
    case 0x45: return 1;
    case 0x46: case 0x4A: return 2;
    case 0x4B: return len > 1 ? 2 + 7 * msg[1] : 0;
    default: return 0;
    }
}

void hl_event(const uint8_t *msg, int len)
{
    if (msg[0] != 0x46) g_changes++;
    if (!greeted) return;
    if (len > EVENT_MAX) {
        /* §5.7: the text is cut to fill the record, at a UTF-8 character boundary; an event
         * whose fixed part does not fit (TERMINALS_UNCONNECTED with many references) is lost */
        int at = text_at(msg, len);
        if (!at || at > EVENT_MAX) { events_lost++; lost_pending = 1; return; }
        len = EVENT_MAX;
        while (len > at && (msg[len] & 0xC0) == 0x80) len--;
    }
    if (ev_count >= EVENT_QUEUE) { events_lost++; lost_pending = 1; return; }
    uint8_t slot = (uint8_t)((ev_head + ev_count) % EVENT_QUEUE);
    memcpy(events[slot], msg, (size_t)len);
    event_len[slot] = (uint8_t)len;
    ev_count++;
}

void hl_event_device(uint8_t code, int dev)
{
    uint8_t m[8];
    const device_t *d = &g_dev[dev];
    m[0] = code;
    put16(m + 1, d->key.vid); put16(m + 3, d->key.pid); put16(m + 5, d->key.serial);
    m[7] = d->node_id;
    hl_event(m, code == 0x41 ? 8 : 7);
}

/* DEVICE_LEFT with why (§5.7): the key, how long it was silent and its beacon interval (ms,
 * u16, saturating), the reason; an old PC reads the key and ignores the rest. */
void hl_event_left(int dev, uint32_t silent_ms, uint16_t interval_ms, const char *why)
{
    uint8_t m[EVENT_MAX + 1];
    const device_t *d = &g_dev[dev];
    int n = (int)strlen(why);
    if (n > EVENT_MAX - 11) n = EVENT_MAX - 11;
    m[0] = 0x42;
    put16(m + 1, d->key.vid); put16(m + 3, d->key.pid); put16(m + 5, d->key.serial);
    put16(m + 7, (uint16_t)(silent_ms > 0xFFFFu ? 0xFFFFu : silent_ms));
    put16(m + 9, interval_ms);
    memcpy(m + 11, why, (size_t)n);
    hl_event(m, n + 11);
}

void hl_event_link(uint8_t code, const link_t *l)
{
    uint8_t m[16];
    m[0] = code;
    put_ref(m + 1, &l->out);
    put_ref(m + 8, &l->in);
    m[15] = node_output_id(&l->out);
    hl_event(m, 16);
}

void hl_event_error(uint8_t kind, const char *text)
{
    uint8_t m[EVENT_MAX + 1];
    int n = (int)strlen(text);
    if (n > EVENT_MAX - 1) n = EVENT_MAX - 1;   /* hl_event cuts it at a character boundary */
    m[0] = 0x46; m[1] = kind;
    memcpy(m + 2, text, (size_t)n);
    hl_event(m, n + 2);
}

/* -- replies ----------------------------------------------------------------------------- */
static uint8_t *body;         /* reply + 2 */
static uint16_t blen;
static char why[200];

/* A refusal with a fixed reason (a literal, no '%' in it: it is the format). */
#define refuse(status, text) (fmt_text(why, sizeof why, text), (status))

static int exact(uint16_t n, uint16_t want, const char *name)
{
    if (n == want) return 0;
    fmt_text(why, sizeof why, "%s is %u bytes, not %u", name, want, n);
    return ST_BAD_LENGTH;
}

static int device_of(const uint8_t *p, int need_present, int *dev)
{
    dev_key_t k = { get16(p), get16(p + 2), get16(p + 4) };
    int d = dev_find(&k);
    if (d < 0 || !g_dev[d].in_system) {
        fmt_text(why, sizeof why, "device %k is not known to the arbitrator", &k);
        return ST_UNKNOWN_DEVICE;
    }
    if (need_present && (!g_dev[d].present || !g_dev[d].node_id)) {
        fmt_text(why, sizeof why, "device %k is not on the bus", &k);
        return ST_DEVICE_ABSENT;
    }
    *dev = d;
    return 0;
}

static int req_status(int r, const char *what)
{
    if (r == REQ_OK) return 0;
    if (r == REQ_REFUSED) { fmt_text(why, sizeof why, "%s: the device refused it", what); return ST_DEVICE_REFUSED; }
    if (r == REQ_TIMEOUT) { fmt_text(why, sizeof why, "%s: no response from the device", what); return ST_DEVICE_TIMEOUT; }
    if (r == REQ_NOWRITE) { fmt_text(why, sizeof why, "another arbitrator is on the bus: no writes"); return ST_OTHER_ARBITRATOR; }
    fmt_text(why, sizeof why, "%s: the device is not on the bus", what);
    return ST_DEVICE_ABSENT;
}

static int sorted_devices(int *order)
{
    int n = 0;
    for (int d = 0; d < MAX_DEVICES; d++) {
        if (!g_dev[d].used || !g_dev[d].in_system) continue;
        int j = n++;
        while (j > 0 && key_cmp(&g_dev[order[j - 1]].key, &g_dev[d].key) > 0) { order[j] = order[j - 1]; j--; }
        order[j] = d;
    }
    return n;
}

static int dev_channels(int dev, int *list)
{
    int n = 0;
    for (int idx = 0; idx < 256 && n < MAX_CH_PER_DEVICE; idx++) {
        int c = ch_of(dev, (uint8_t)idx);
        if (c >= 0) list[n++] = c;
    }
    return n;
}

static int channel_record(int c, uint8_t *p)
{
    const channel_t *ch = &g_ch[c];
    int n = 0;
    p[n++] = ch->index; p[n++] = ch->dir; p[n++] = ch->enabled ? 1 : 0;
    put16(p + n, ch->type); n += 2;
    put16(p + n, ch->profile); n += 2;
    p[n++] = ch->dir == DIR_OUT ? node_of_output(ch->dev, ch->index) : 0;
    if (ch->dir == DIR_IN) {
        put16(p + n, ch->term_profile); n += 2;
        put16(p + n, ch->src.vid); n += 2;
        put16(p + n, ch->src.pid); n += 2;
        put16(p + n, ch->src.serial); n += 2;
        p[n++] = ch->src.index;
        put16(p + n, ch->src.type); n += 2;
        put16(p + n, ch->src.profile); n += 2;
    }
    for (int w = 0; w < 2; w++) {
        uint32_t m = w ? ch->des : ch->req;
        int at = n++;
        p[at] = 0;
        for (int i = 0; i < 32; i++) if (m & (1u << i)) { put16(p + n, (uint16_t)i); n += 2; p[at]++; }
    }
    p[n++] = ch->desc_len;
    memcpy(p + n, ch->desc, ch->desc_len);
    return n + ch->desc_len;
}

/* A channel page from list position `start` in `room` bytes: next position (0 = done), records. */
static int channel_page(int dev, int start, uint8_t *p, int room)
{
    int list[MAX_CH_PER_DEVICE], n = dev_channels(dev, list), used = 1, pos = start;
    uint8_t rec[64 + CH_DESC_MAX];
    while (pos < n) {
        int k = channel_record(list[pos], rec);
        if (used + k > room) break;
        memcpy(p + used, rec, (size_t)k);
        used += k;
        pos++;
    }
    p[0] = (uint8_t)(pos < n ? pos : 0);
    return used;
}

static int sorted_links(uint16_t *order)
{
    int n = 0;
    for (uint16_t i = 0; i < g_nlinks; i++) {
        int j = n++;
        while (j > 0 && link_cmp(&g_links[order[j - 1]], &g_links[i]) > 0) { order[j] = order[j - 1]; j--; }
        order[j] = i;
    }
    return n;
}

static int stage_chunk(int area, const uint8_t *b, uint16_t n, uint16_t *have, uint16_t total,
                       const char *what)
{
    uint16_t offset = get16(b);
    uint16_t k = (uint16_t)(n - 2);
    if (offset > *have) { fmt_text(why, sizeof why, "expected offset %u, not %u", *have, offset); return ST_BAD_OFFSET; }
    if ((uint32_t)offset + k > total) {
        fmt_text(why, sizeof why, "%u bytes is past the announced %u", (unsigned)(offset + k), total);
        return ST_BAD_OFFSET;
    }
    int bad = area < 0 ? mem_write_chunk(offset, b + 2, k) : port_nvm_write(area, offset, b + 2, k);
    if (bad) { fmt_text(why, sizeof why, "the %s could not be written to memory", what); return ST_STORAGE; }
    if (offset + k > *have) *have = (uint16_t)(offset + k);
    put16(body, *have);
    blen = 2;
    return 0;
}

static int staged_whole(int area, uint32_t base, uint16_t have, uint16_t total, uint16_t crc,
                        const char *what)
{
    uint8_t buf[64];
    uint16_t c = 0xFFFF;
    if (have != total) {
        fmt_text(why, sizeof why, "%u of %u bytes received; nothing done", have, total);
        return ST_BAD_OFFSET;
    }
    for (uint16_t off = 0; off < total; off = (uint16_t)(off + sizeof buf)) {
        uint16_t k = (uint16_t)(total - off < (int)sizeof buf ? total - off : (int)sizeof buf);
        if (port_nvm_read(area, base + off, buf, k)) { fmt_text(why, sizeof why, "memory read failed"); return ST_STORAGE; }
        c = crc16_update(c, buf, k);
    }
    if (c != crc) {
        fmt_text(why, sizeof why, "CRC 0x%x of the bytes received is not the announced 0x%x; "
                 "nothing done", c, crc);
        return ST_CHECKSUM;
    }
    (void)what;
    return 0;
}

static int blob_reply(int area, uint32_t base, uint16_t len, uint16_t crc, const uint8_t *b,
                      uint16_t n, const char *what)
{
    int st = exact(n, 2, what);
    if (st) return st;
    uint16_t offset = get16(b);
    if (offset > len) {
        fmt_text(why, sizeof why, "offset %u is past the %u bytes", offset, len);
        return ST_BAD_OFFSET;
    }
    uint16_t k = (uint16_t)(len - offset > CHUNK ? CHUNK : len - offset);
    put16(body, len); put16(body + 2, crc);
    if (k && (area < 0 ? mem_read(offset, body + 4, k) : port_nvm_read(area, base + offset, body + 4, k))) {
        fmt_text(why, sizeof why, "memory read failed");
        return ST_STORAGE;
    }
    blen = (uint16_t)(4 + k);
    return 0;
}

static int handle(uint8_t code, const uint8_t *b, uint16_t n)
{
    int st, dev = -1;
    switch (code) {
    case 0x01: {   /* HELLO */
        if (n < 1) return exact(n, 3, "HELLO");
        if (b[0] != 2) {
            greeted = 0;
            fmt_text(why, sizeof why, "this arbitrator speaks host-link version 2, not version %u", b[0]);
            return ST_VERSION;
        }
        greeted = 1;
#if MONITOR
        mon_stop();                       /* a new session starts without the monitor */
#endif
        static const char name[] = "pdcp-fw 0.1 reference arbitrator";
        body[0] = 2; put16(body + 1, CAPABILITIES); body[3] = MAX_PAYLOAD;
        memcpy(body + 4, name, sizeof name - 1);
        blen = (uint16_t)(4 + sizeof name - 1);
        return 0;
    }
    case 0x02: {   /* STATUS */
        if ((st = exact(n, 0, "STATUS"))) return st;
        int order[MAX_DEVICES];
        int nd = sorted_devices(order);
        body[0] = (uint8_t)((arb_settled() ? 1 : 0) | (g_startup_done ? 2 : 0) | (g_other_heard ? 4 : 0));
        body[1] = (uint8_t)(nd > 255 ? 255 : nd);
        put16(body + 2, g_nlinks); put16(body + 4, g_changes); put16(body + 6, events_lost);
        blen = 8;
        return 0;
    }
    case 0x03: {   /* LIST_DEVICES */
        if ((st = exact(n, 2, "LIST_DEVICES"))) return st;
        int order[MAX_DEVICES], nd = sorted_devices(order), start = get16(b);
        put16(body, (uint16_t)nd); put16(body + 2, (uint16_t)start);
        blen = 4;
        for (int i = start; i < nd && i < start + 27; i++) {
            const device_t *d = &g_dev[order[i]];
            int list[MAX_CH_PER_DEVICE];
            uint8_t *p = body + blen;
            put16(p, d->key.vid); put16(p + 2, d->key.pid); put16(p + 4, d->key.serial);
            p[6] = d->present ? d->node_id : 0; p[7] = d->present ? 1 : 0;
            p[8] = (uint8_t)dev_channels(order[i], list);
            blen = (uint16_t)(blen + 9);
        }
        return 0;
    }
    case 0x04: {   /* GET_DEVICE */
        if ((st = exact(n, 6, "GET_DEVICE"))) return st;
        if ((st = device_of(b, 0, &dev))) return st;
        const device_t *d = &g_dev[dev];
        int list[MAX_CH_PER_DEVICE];
        uint8_t *p = body;
        p[0] = d->present ? d->node_id : 0; p[1] = d->present ? 1 : 0;
        put16(p + 2, d->fw); put16(p + 4, d->hw); put16(p + 6, d->dtype); put16(p + 8, d->dprofile);
        put16(p + 10, d->beacon_ms); put16(p + 12, d->ack_ms); put16(p + 14, d->bind_ms);
        put32(p + 16, d->ean_lo); put32(p + 20, d->ean_hi);
        p[24] = (uint8_t)dev_channels(dev, list);
        p[25] = d->desc_len;
        memcpy(p + 26, d->desc, d->desc_len);
        blen = (uint16_t)(26 + d->desc_len);
        blen = (uint16_t)(blen + channel_page(dev, 0, body + blen, BODY_ROOM - blen));
        return 0;
    }
    case 0x05: {   /* GET_CHANNELS */
        if ((st = exact(n, 7, "GET_CHANNELS"))) return st;
        if ((st = device_of(b, 0, &dev))) return st;
        blen = (uint16_t)channel_page(dev, b[6], body, BODY_ROOM);
        return 0;
    }
    case 0x06: {   /* LIST_LINKS */
        if ((st = exact(n, 2, "LIST_LINKS"))) return st;
        static uint16_t order[MAX_LINKS];
        int nl = sorted_links(order), start = get16(b);
        put16(body, (uint16_t)nl); put16(body + 2, (uint16_t)start);
        blen = 4;
        for (int i = start; i < nl && i < start + 17; i++) {
            blen = (uint16_t)(blen + put_ref(body + blen, &g_links[order[i]].out));
            blen = (uint16_t)(blen + put_ref(body + blen, &g_links[order[i]].in));
        }
        return 0;
    }
    case 0x07: {   /* GET_PARAM */
        if ((st = exact(n, 10, "GET_PARAM"))) return st;
        uint16_t offset = get16(b + 8);
        if (offset == 0) {
            if ((st = device_of(b, 1, &dev))) return st;
            value_valid = 0;
            st = req_status(arb_get_param(dev, b[7], b[6], value, VALUE_MAX, &value_len), "GET_PARAM");
            if (st) return st;
            memcpy(value_addr, b, 8);
            value_valid = 1;
        } else if (!value_valid || memcmp(value_addr, b, 8)) {
            return refuse(ST_BAD_OFFSET, "read this parameter from offset 0 first");
        }
        if (offset > value_len) {
            fmt_text(why, sizeof why, "offset %u is past the value's %u bytes", offset, value_len);
            return ST_BAD_OFFSET;
        }
        uint16_t k = (uint16_t)(value_len - offset > CHUNK ? CHUNK : value_len - offset);
        put16(body, offset); put16(body + 2, value_len);
        memcpy(body + 4, value + offset, k);
        blen = (uint16_t)(4 + k);
        return 0;
    }
    case 0x08: {   /* SET_PARAM */
        if (n < 12) { fmt_text(why, sizeof why, "SET_PARAM: %u bytes, needs 12", n); return ST_BAD_LENGTH; }
        uint16_t offset = get16(b + 8), total = get16(b + 10), k = (uint16_t)(n - 12);
        if (total > VALUE_MAX) {
            fmt_text(why, sizeof why, "a value of %u bytes is more than this arbitrator moves (%u)",
                     total, (unsigned)VALUE_MAX);
            return ST_TOO_LARGE;
        }
        if (offset == 0) { memcpy(set_addr, b, 8); set_total = total; set_have = 0; set_active = 1; }
        if (!set_active || memcmp(set_addr, b, 8) || set_total != total)
            return refuse(ST_NO_TRANSFER, "start the value at offset 0");
        if (offset != set_have) {
            fmt_text(why, sizeof why, "expected offset %u, not %u", set_have, offset);
            return ST_BAD_OFFSET;
        }
        if ((uint32_t)offset + k > total) {
            fmt_text(why, sizeof why, "%u bytes is past the value's %u", (unsigned)(offset + k), total);
            return ST_BAD_OFFSET;
        }
        value_valid = 0;
        memcpy(value + offset, b + 12, k);
        set_have = (uint16_t)(set_have + k);
        if (set_have < total) { put16(body, set_have); body[2] = 0; blen = 3; return 0; }
        set_active = 0;
        if ((st = device_of(b, 1, &dev))) return st;
        if (arb_managed(dev, b[7], b[6])) {
            fmt_text(why, sizeof why, "parameter %u of channel %u is managed by the arbitrator "
                     "(node IDs follow binding and links)", b[7], b[6]);
            return ST_MANAGED;
        }
        if ((st = req_status(arb_set_param(dev, b[7], b[6], value, total), "SET_PARAM"))) return st;
        put16(body, total); body[2] = 1; blen = 3;
        return 0;
    }
    case 0x09: case 0x0A: {   /* ADD_LINK, REMOVE_LINK */
        if ((st = exact(n, 14, code == 9 ? "ADD_LINK" : "REMOVE_LINK"))) return st;
        link_t l;
        get_ref(b, &l.out); get_ref(b + 7, &l.in);
        return code == 9 ? arb_add_link(&l, why, sizeof why) : arb_remove_link(&l, why, sizeof why);
    }
    case 0x0B: {   /* SUSPEND */
        if ((st = exact(n, 8, "SUSPEND"))) return st;
        if ((st = device_of(b, 1, &dev))) return st;
        return req_status(req_simple(g_dev[dev].node_id, 0x08, b + 6, 2), "SUSPEND");
    }
    case 0x0C: case 0x0D: {   /* RELEASE, RESET_DEVICE */
        if ((st = exact(n, 6, code == 0x0C ? "RELEASE" : "RESET_DEVICE"))) return st;
        if ((st = device_of(b, 1, &dev))) return st;
        return req_status(req_simple(g_dev[dev].node_id, code == 0x0C ? 0x09 : 0x0B, 0, 0),
                          code == 0x0C ? "RELEASE" : "RESET_DEVICE");
    }
    case 0x0E: {   /* CONFIG_INFO */
        if ((st = exact(n, 0, "CONFIG_INFO"))) return st;
        uint32_t len; uint16_t crc;
        mem_current(&len, &crc, 0);
        put16(body, (uint16_t)len); put16(body + 2, crc);
        blen = 4;
        return 0;
    }
    case 0x0F: {   /* CONFIG_READ */
        uint32_t len; uint16_t crc;
        mem_current(&len, &crc, 0);
        return blob_reply(-1, 0, (uint16_t)len, crc, b, n, "CONFIG_READ");
    }
    case 0x10: {   /* CONFIG_WRITE_BEGIN */
        if ((st = exact(n, 4, "CONFIG_WRITE_BEGIN"))) return st;
        cfgw.active = 0;
        if (get16(b) > MEM_CAPACITY) {
            fmt_text(why, sizeof why, "a configuration of %u bytes does not fit the memory (%u)",
                     get16(b), (unsigned)MEM_CAPACITY);
            return ST_TOO_LARGE;
        }
        if (!g_may_write && g_other_heard) return refuse(ST_OTHER_ARBITRATOR, "another arbitrator is on the bus: no writes");
        mem_begin();
        cfgw.active = 1; cfgw.total = get16(b); cfgw.crc = get16(b + 2); cfgw.have = 0;
        return 0;
    }
    case 0x11: {   /* CONFIG_WRITE_CHUNK */
        if (n < 2) { fmt_text(why, sizeof why, "CONFIG_WRITE_CHUNK: %u bytes, needs 2", n); return ST_BAD_LENGTH; }
        if (!cfgw.active) return refuse(ST_NO_TRANSFER, "no configuration is being sent (BEGIN first)");
        return stage_chunk(-1, b, n, &cfgw.have, cfgw.total, "configuration");
    }
    case 0x12: {   /* CONFIG_WRITE_COMMIT */
        if ((st = exact(n, 0, "CONFIG_WRITE_COMMIT"))) return st;
        if (!cfgw.active) return refuse(ST_NO_TRANSFER, "no configuration is being sent (BEGIN first)");
        cfgw.active = 0;
        int spare = mem_begin();
        if ((st = staged_whole(spare, 24, cfgw.have, cfgw.total, cfgw.crc, "configuration"))) return st;
        char reason[120];
        if (config_decode(spare, 24, cfgw.total, reason, sizeof reason)) {
            fmt_text(why, sizeof why, "%s; nothing stored", reason);
            return ST_BAD_CONFIGURATION;
        }
        uint16_t flags;
        mem_current(0, 0, &flags);
        if (mem_commit(cfgw.total, flags)) return refuse(ST_STORAGE, "the memory write failed; the previous configuration stays");
        uint32_t len; uint16_t crc;
        mem_current(&len, &crc, 0);
        put16(body, (uint16_t)len); put16(body + 2, crc);
        blen = 4;
        g_changes++;
        return 0;
    }
    case 0x13: {   /* TRANSACT_BEGIN */
        if ((st = exact(n, 4, "TRANSACT_BEGIN"))) return st;
        chg.active = 0;
        if (get16(b) > MAX_CHANGE || get16(b) > port_nvm_capacity(2)) {
            fmt_text(why, sizeof why, "a change of %u bytes is more than this arbitrator takes (%u)",
                     get16(b), (unsigned)(MAX_CHANGE < port_nvm_capacity(2) ? MAX_CHANGE : port_nvm_capacity(2)));
            return ST_TOO_LARGE;
        }
        chg.active = 1; chg.total = get16(b); chg.crc = get16(b + 2); chg.have = 0;
        return 0;
    }
    case 0x14: {   /* TRANSACT_CHUNK */
        if (n < 2) { fmt_text(why, sizeof why, "TRANSACT_CHUNK: %u bytes, needs 2", n); return ST_BAD_LENGTH; }
        if (!chg.active) return refuse(ST_NO_TRANSFER, "no change is being sent (BEGIN first)");
        return stage_chunk(2, b, n, &chg.have, chg.total, "change");
    }
    case 0x16: {   /* TRANSACT_RUN */
        if ((st = exact(n, 0, "TRANSACT_RUN"))) return st;
        if (!chg.active) return refuse(ST_NO_TRANSFER, "no change is being sent (BEGIN first)");
        chg.active = 0;
        if ((st = staged_whole(2, 0, chg.have, chg.total, chg.crc, "change"))) return st;
        uint32_t rlen; uint16_t rcrc;
        result_valid = 0;
        if ((st = txn_run(chg.total, &rlen, &rcrc, why, sizeof why))) return st;
        result_valid = 1; result_len = (uint16_t)rlen; result_crc = rcrc;
        put16(body, result_len); put16(body + 2, result_crc);
        blen = 4;
        return 0;
    }
    case 0x18:     /* RESULT_READ */
        if (n == 2 && !result_valid) return refuse(ST_NO_TRANSFER, "no transaction result (TRANSACT_RUN first)");
        return blob_reply(3, 0, result_len, result_crc, b, n, "RESULT_READ");
    case 0x15:     /* GET_POLICY */
        if ((st = exact(n, 0, "GET_POLICY"))) return st;
        body[0] = (uint8_t)mem_policy_autoconfigure();
        blen = 1;
        return 0;
    case 0x17:     /* MONITOR */
#if MONITOR
        if ((st = exact(n, 2, "MONITOR"))) return st;
        put16(body, mon_configure(b[0], b[1]));
        blen = 2;
        return 0;
#else
        return refuse(ST_UNSUPPORTED, "this arbitrator has no monitor (capability bit 0)");
#endif
    default:
        fmt_text(why, sizeof why, "unknown request 0x%x", code);
        /* "0x003E" → "0x3E", as PDCP Studio words it */
        memmove(why + 18, why + 20, strlen(why + 20) + 1);
        return ST_UNKNOWN_REQUEST;
    }
}

/* Answered without CAN traffic (from the tables and the memory), so inside pump(): they do not
 * wait for a set-up or a plan the main loop is running. */
static int is_table_request(uint8_t code)
{
    switch (code) {
    case 0x07: case 0x08: case 0x09: case 0x0A: case 0x0B: case 0x0C: case 0x0D: case 0x16:
        return 0;
    default:
        return 1;
    }
}

static void answer(const uint8_t *msg, uint16_t n)
{
    uint8_t code = msg[0];
    body = reply + 2;
    blen = 0;
    why[0] = 0;
    int st;
    if (code >= 0x40) {            /* an event's or a reply's code: answered, never silence */
        fmt_text(why, sizeof why, "0x%x is not a request code (requests are 0x01-0x3F)", code);
        memmove(why + 2, why + 4, strlen(why + 4) + 1);         /* "0x0041" → "0x41" */
        st = ST_UNKNOWN_REQUEST;
    } else if (code > 0x01 && code <= 0x18 && !greeted) {   /* the codes served here */
        st = refuse(ST_NOT_GREETED, "send HELLO first");
    } else {
        st = handle(code, msg + 1, (uint16_t)(n - 1));
    }
    reply[0] = (uint8_t)(code | 0x80);
    reply[1] = (uint8_t)st;
    if (st) {
        uint16_t k = (uint16_t)strlen(why);
        memcpy(reply + 2, why, k);
        blen = k;
    }
    reply_len = (uint16_t)(2 + blen);
    pump_out();
}

void hl_poll(void)
{
    if (inflight_len && (int32_t)(port_millis() - deadline) >= 0) {
        if (attempts >= MAX_ATTEMPTS) {
            inflight_len = 0;
            forget_host();
            port_log("host link: a frame was given up; the PC must greet again");
        } else {
            transmit();
        }
    }
    if (mailbox_len && !reply_len && !handling && is_table_request(mailbox[0])) {
        answer(mailbox, mailbox_len);     /* no CAN traffic: nothing arrives meanwhile */
        mailbox_len = 0;
    }
    pump_out();
}

void hl_service(void)
{
    if (!mailbox_len || reply_len || handling) return;
    handling = 1;                 /* the mailbox stays taken while the request runs */
    answer(mailbox, mailbox_len);
    mailbox_len = 0;
    handling = 0;
}

void hl_init(void)
{
    rx_len = 0;
    tx_seq = rx_expected = 0;
    last_ok = 0;
}
