/* The AVR port (ATmega1284P at 16 MHz): for the size report, and a start for real hardware.
 *
 * USART0: the host link (125000 baud, 0 % error at 16 MHz: U2X, UBRR 15 — 128000 is not
 * reachable from 16 MHz).  USART1: CAN frames as SLCAN text to a CAN adapter (an MCP2515 or a
 * USB-CAN stick in SLCAN mode would replace it on a real board).  Timer0: the millisecond
 * tick.  EEPROM (4 KB): slots A and B of the stored configuration (24 + MEM_CAPACITY each),
 * then the transaction's change and result areas in what is left.
 */
#include <avr/io.h>
#include <avr/interrupt.h>
#include <avr/eeprom.h>
#include <string.h>
#include "../../src/port.h"
#include "../../src/arb.h"
#include "../common/slcan.h"

static volatile uint32_t ticks;
ISR(TIMER0_COMPA_vect) { ticks++; }

#define RX_RING 64
static volatile uint8_t host_rx[RX_RING], host_head, host_tail;
ISR(USART0_RX_vect)
{
    uint8_t b = UDR0, next = (uint8_t)((host_head + 1) % RX_RING);
    if (next != host_tail) { host_rx[host_head] = b; host_head = next; }
}

void port_init(void)
{
    UCSR0A = _BV(U2X0); UBRR0 = 15;                  /* 125000 baud */
    UCSR0B = _BV(RXEN0) | _BV(TXEN0) | _BV(RXCIE0);
    UCSR1A = _BV(U2X1); UBRR1 = 16;                  /* 115200 baud (2.1 %) */
    UCSR1B = _BV(RXEN1) | _BV(TXEN1);
    TCCR0A = _BV(WGM01); TCCR0B = _BV(CS01) | _BV(CS00); OCR0A = 249;   /* 1 ms */
    TIMSK0 = _BV(OCIE0A);
    sei();
}

uint32_t port_millis(void)
{
    uint32_t t;
    cli(); t = ticks; sei();
    return t;
}

int port_host_read(uint8_t *buf, int max)
{
    int n = 0;
    while (n < max && host_tail != host_head) {
        buf[n++] = host_rx[host_tail];
        host_tail = (uint8_t)((host_tail + 1) % RX_RING);
    }
    return n;
}

void port_host_write(const uint8_t *buf, int len)
{
    for (int i = 0; i < len; i++) { while (!(UCSR0A & _BV(UDRE0))) {} UDR0 = buf[i]; }
}

static slcan_rx_t can_rx;

int port_can_ready(void) { return 1; }   /* a board's CAN side is up at reset */

static void can_out(const char *s, int n)
{
    for (int i = 0; i < n; i++) { while (!(UCSR1A & _BV(UDRE1))) {} UDR1 = (uint8_t)s[i]; }
}

int port_can_read(uint16_t *id, uint8_t *data, uint8_t *len)
{
    while (UCSR1A & _BV(RXC1)) {
        int r = slcan_feed(&can_rx, (char)UDR1, id, data, len);
        if (r == 1) return 1;
        if (r >= 2) can_out("\r", 1);
    }
    return 0;
}

void port_can_write(uint16_t id, const uint8_t *data, uint8_t len)
{
    char line[24];
    can_out(line, slcan_format(line, id, data, len));
}

#define SLOT (24u + MEM_CAPACITY)
static const uint16_t area_base[NVM_AREAS] = { 0, SLOT, 2 * SLOT, 2 * SLOT + 1024 };

uint32_t port_nvm_capacity(int area)
{
    return area < 2 ? SLOT : area == 2 ? 1024u : (uint32_t)(E2END + 1) - area_base[3];
}

int port_nvm_read(int area, uint32_t offset, uint8_t *buf, uint32_t len)
{
    if (area < 0 || area >= NVM_AREAS || offset + len > port_nvm_capacity(area)) return -1;
    eeprom_read_block(buf, (const void *)(uintptr_t)(area_base[area] + offset), len);
    return 0;
}

int port_nvm_write(int area, uint32_t offset, const uint8_t *buf, uint32_t len)
{
    if (area < 0 || area >= NVM_AREAS || offset + len > port_nvm_capacity(area)) return -1;
    eeprom_update_block(buf, (void *)(uintptr_t)(area_base[area] + offset), len);
    return 0;
}

int port_nvm_sync(void) { eeprom_busy_wait(); return 0; }

void port_log(const char *text) { (void)text; }
