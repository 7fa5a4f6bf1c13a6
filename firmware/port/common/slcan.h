/* SLCAN text frames ("t1230A..\r"), as python-can's slcan interface speaks them: the CAN side
 * of the QEMU and POSIX ports, bridged to any python-can bus by `pdcp-studio can-bridge`. */
#ifndef PDCP_SLCAN_H
#define PDCP_SLCAN_H
#include <stdint.h>

typedef struct {
    char line[32];
    uint8_t len, overflow;
} slcan_rx_t;

/* Feed one character; 1 when a standard data frame is complete (id, data, len set),
 * 2 when a command line ended that wants the "\r" acknowledgement, 3 when that command opened
 * the channel ("O" or "L"), else 0. */
int slcan_feed(slcan_rx_t *rx, char c, uint16_t *id, uint8_t *data, uint8_t *len);
/* "tIIIL<data>\r" for a standard frame; returns its length (at most 22). */
int slcan_format(char *out, uint16_t id, const uint8_t *data, uint8_t len);
#endif
