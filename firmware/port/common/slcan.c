#include "slcan.h"

static int hexval(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
}

int slcan_feed(slcan_rx_t *rx, char c, uint16_t *id, uint8_t *data, uint8_t *len)
{
    if (c != '\r' && c != '\n') {
        if (rx->len < sizeof rx->line) rx->line[rx->len++] = c;
        else rx->overflow = 1;
        return 0;
    }
    int n = rx->len, bad = rx->overflow;
    rx->len = 0;
    rx->overflow = 0;
    if (!n || bad) return 0;
    const char *s = rx->line;
    if (s[0] == 'O' || s[0] == 'L') return 3;
    if (s[0] != 't') return s[0] == 'T' || s[0] == 'r' || s[0] == 'R' ? 0 : 2;
    if (n < 5) return 0;
    int v = 0;
    for (int i = 1; i <= 3; i++) {
        int h = hexval(s[i]);
        if (h < 0) return 0;
        v = v * 16 + h;
    }
    int dlc = hexval(s[4]);
    if (dlc < 0 || dlc > 8 || n < 5 + 2 * dlc) return 0;
    for (int i = 0; i < dlc; i++) {
        int hi = hexval(s[5 + 2 * i]), lo = hexval(s[6 + 2 * i]);
        if (hi < 0 || lo < 0) return 0;
        data[i] = (uint8_t)(hi * 16 + lo);
    }
    *id = (uint16_t)(v & 0x7FF);
    *len = (uint8_t)dlc;
    return 1;
}

int slcan_format(char *out, uint16_t id, const uint8_t *data, uint8_t len)
{
    static const char hex[] = "0123456789ABCDEF";
    int n = 0;
    out[n++] = 't';
    out[n++] = hex[(id >> 8) & 7];
    out[n++] = hex[(id >> 4) & 15];
    out[n++] = hex[id & 15];
    out[n++] = hex[len & 15];
    for (int i = 0; i < len; i++) {
        out[n++] = hex[data[i] >> 4];
        out[n++] = hex[data[i] & 15];
    }
    out[n++] = '\r';
    return n;
}
