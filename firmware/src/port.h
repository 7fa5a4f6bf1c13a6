/* The port layer: everything the arbitrator core needs from a board, and nothing more.
 *
 * A port provides a host UART (the host link, docs/host-link.md), CAN frames in and out,
 * a millisecond tick and a small non-volatile memory of areas.  All calls are non-blocking;
 * the core polls.  Ports: port/lm3s6965 (QEMU's lm3s6965evb: UART0 = host link, UART1 = CAN
 * as SLCAN text, NVM = a host file through semihosting), port/posix (two file descriptors and
 * a file, for fast tests on the build machine) and port/avr (ATmega1284P, size report).
 */
#ifndef PDCP_PORT_H
#define PDCP_PORT_H

#include <stdint.h>

void port_init(void);

/* Milliseconds since start (wraps after 49 days; the core compares differences). */
uint32_t port_millis(void);

/* Host link UART: read what has arrived (up to max bytes, 0 when none); write all bytes. */
int port_host_read(uint8_t *buf, int max);
void port_host_write(const uint8_t *buf, int len);

/* CAN 2.0A frames: 1 and the frame when one arrived, 0 when none.  Extended, remote and
 * error frames are not delivered (a port drops them). */
int port_can_read(uint16_t *id, uint8_t *data, uint8_t *len);
void port_can_write(uint16_t id, const uint8_t *data, uint8_t len);
/* 1 once the CAN side is on the bus (a CAN controller: at once; the SLCAN ports: when the
 * line is opened with "O", i.e. when the bridge has joined the bus).  Listening for another
 * arbitrator starts then. */
int port_can_ready(void);

/* Non-volatile memory: NVM_AREAS areas of up to nvm_capacity(area) bytes.  Areas 0 and 1 are
 * the stored configuration's two slots (header + payload, memory.py's layout), area 2 holds a
 * transaction's staged change and area 3 its result.  Returns 0 on success. */
#define NVM_AREAS 4
uint32_t port_nvm_capacity(int area);
int port_nvm_read(int area, uint32_t offset, uint8_t *buf, uint32_t len);
int port_nvm_write(int area, uint32_t offset, const uint8_t *buf, uint32_t len);
int port_nvm_sync(void);

/* A line for whoever watches the board (semihosting stderr, a debug UART; may do nothing). */
void port_log(const char *text);

#endif
