/* Requests to devices on the CAN bus (reference §1 function codes), one at a time.
 *
 * A request is sent and its response waited for while pump() keeps everything else going
 * (bind answers, beacons, the host link's ACKs).  Each attempt waits RESPONSE_TIMEOUT_MS;
 * REQUEST_RETRIES more attempts follow a silent device (bus/arbitrator/reading/requests.py).
 * A device that answers "use bulk data transfer" (code 2) is followed into the bulk flow:
 * Configure Get/Set Bulk, 0x0E packets of 6 bytes from packet ID 1, 0x8E after the last.
 */
#include <string.h>
#include "arb.h"
#include "port.h"

#define PRIO_NORMAL 1

static struct {
    uint8_t active, node, code, check, param, chan;
    uint8_t got, len;
    uint8_t frame[8];
    uint8_t *buf;          /* bulk packets land here */
    uint16_t size, have;
    uint8_t next_packet, bad;
} W;

void can_send(uint16_t id, const uint8_t *data, uint8_t len)
{
#if MONITOR
    mon_frame(id, data, len);
#endif
    port_can_write(id, data, len);
}

void can_send_arb(uint8_t node, const uint8_t *data, uint8_t len)
{
    if (!g_may_write) return;
    can_send((uint16_t)((PRIO_NORMAL << 9) | (1 << 8) | node), data, len);
}

int req_on_frame(uint16_t id, const uint8_t *data, uint8_t len)
{
    if (!W.active || (id >> 8 & 1) || (id >> 9) == 3 || (id & 0xFF) != W.node || !len)
        return 0;
    if (W.code == 0x0E) {                          /* collecting bulk packets */
        if (data[0] != 0x0E || len < 2) return 0;
        if (data[1] != W.next_packet) { W.bad = 1; W.got = 1; return 1; }
        uint8_t n = (uint8_t)(len - 2);
        if (n > W.size - W.have) n = (uint8_t)(W.size - W.have);
        memcpy(W.buf + W.have, data + 2, n);
        W.have = (uint16_t)(W.have + n);
        W.next_packet++;
        if (W.have >= W.size) W.got = 1;
        return 1;
    }
    if (data[0] != W.code) return 0;
    if (W.check && (len < 4 || data[2] != W.param || data[3] != W.chan)) return 0;
    memcpy(W.frame, data, len);
    W.len = len;
    W.got = 1;
    return 1;
}

static void arm(uint8_t node, uint8_t code, int check, uint8_t param, uint8_t chan)
{
    W.active = 1; W.node = node; W.code = code; W.check = (uint8_t)check;
    W.param = param; W.chan = chan; W.got = 0; W.bad = 0;
}

static int wait(void)
{
    uint32_t start = port_millis();
    while (!W.got && port_millis() - start < RESPONSE_TIMEOUT_MS) pump();
    int got = W.got;
    W.active = 0;
    return got;
}

static void send_req(uint8_t node, const uint8_t *data, uint8_t len)
{
    can_send_arb(node, data, len);
}

static int bulk_get(uint8_t node, uint8_t param, uint8_t chan, uint8_t *value, uint16_t room,
                    uint16_t *len)
{
    uint8_t f[3] = { 0x0C, param, chan };
    arm(node, 0x8C, 1, param, chan);
    send_req(node, f, 3);
    if (!wait()) return REQ_TIMEOUT;
    if (W.len < 6 || W.frame[1] != 1) return REQ_REFUSED;
    uint16_t size = get16(W.frame + 4);
    if (size > room) return REQ_REFUSED;
    *len = size;
    if (size) {
        arm(node, 0x0E, 0, 0, 0);
        W.buf = value; W.size = size; W.have = 0; W.next_packet = 1;
        W.active = 1;
        uint32_t start = port_millis();
        while (!W.got && port_millis() - start < RESPONSE_TIMEOUT_MS * 4u) pump();
        W.active = 0;
        if (!W.got || W.bad) {
            uint8_t nak[2] = { 0x8E, 0 };
            send_req(node, nak, 2);
            return REQ_TIMEOUT;
        }
    }
    uint8_t ok[2] = { 0x8E, 1 };
    send_req(node, ok, 2);
    return REQ_OK;
}

int req_get(uint8_t node, uint8_t param, uint8_t chan, uint8_t *value, uint16_t room,
            uint16_t *len)
{
    int bulk = 0;
    if (!g_may_write) return REQ_NOWRITE;
    for (int attempt = 0; attempt <= REQUEST_RETRIES; attempt++) {
        if (!bulk) {
            uint8_t f[3] = { 0x03, param, chan };
            arm(node, 0x83, 1, param, chan);
            send_req(node, f, 3);
            if (!wait()) continue;
            if (W.frame[1] == 1) {
                uint8_t n = (uint8_t)(W.len > 4 ? W.len - 4 : 0);
                if (n > room) n = (uint8_t)room;
                memcpy(value, W.frame + 4, n);
                *len = n;
                return REQ_OK;
            }
            if (W.frame[1] != 2) return REQ_REFUSED;
            bulk = 1;
        }
        int r = bulk_get(node, param, chan, value, room, len);
        if (r != REQ_TIMEOUT) return r;
    }
    return REQ_TIMEOUT;
}

static int bulk_set(uint8_t node, uint8_t param, uint8_t chan, const uint8_t *value,
                    uint16_t len)
{
    uint8_t f[8] = { 0x0D, param, chan, (uint8_t)len, (uint8_t)(len >> 8) };
    arm(node, 0x8D, 1, param, chan);
    send_req(node, f, 5);
    if (!wait()) return REQ_TIMEOUT;
    if (W.frame[1] != 1) return REQ_REFUSED;
    arm(node, 0x8E, 0, 0, 0);
    uint8_t packet = 1;
    for (uint16_t off = 0; off < len; off = (uint16_t)(off + 6)) {
        uint8_t n = (uint8_t)(len - off > 6 ? 6 : len - off);
        f[0] = 0x0E; f[1] = packet++;
        memcpy(f + 2, value + off, n);
        send_req(node, f, (uint8_t)(2 + n));
    }
    if (!wait()) return REQ_TIMEOUT;
    return W.frame[1] == 1 ? REQ_OK : REQ_TIMEOUT;
}

int req_set(uint8_t node, uint8_t param, uint8_t chan, const uint8_t *value, uint16_t len)
{
    int bulk = len > 4;
    if (!g_may_write) return REQ_NOWRITE;
    for (int attempt = 0; attempt <= REQUEST_RETRIES; attempt++) {
        if (!bulk) {
            uint8_t f[8] = { 0x04, param, chan };
            memcpy(f + 3, value, len);
            arm(node, 0x84, 1, param, chan);
            send_req(node, f, (uint8_t)(3 + len));
            if (!wait()) continue;
            if (W.frame[1] == 1) return REQ_OK;
            if (W.frame[1] != 2) return REQ_REFUSED;
            bulk = 1;
        }
        int r = bulk_set(node, param, chan, value, len);
        if (r != REQ_TIMEOUT) return r;
    }
    return REQ_TIMEOUT;
}

int req_simple(uint8_t node, uint8_t code, const uint8_t *body, uint8_t blen)
{
    uint8_t f[8] = { code };
    if (!g_may_write) return REQ_NOWRITE;
    memcpy(f + 1, body, blen);
    for (int attempt = 0; attempt <= REQUEST_RETRIES; attempt++) {
        arm(node, (uint8_t)(code | 0x80), 0, 0, 0);
        send_req(node, f, (uint8_t)(1 + blen));
        if (!wait()) continue;
        return W.len >= 2 && W.frame[1] == 1 ? REQ_OK : REQ_REFUSED;
    }
    return REQ_TIMEOUT;
}
