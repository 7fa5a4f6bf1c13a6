/* The reference arbitrator's main loop: pump the bus and the host link, answer a request,
 * do the arbitrator's own work (set-ups, departures, start-up, the duty cycle). */
#include "arb.h"
#include "port.h"

int main(void)
{
    port_init();
    hl_init();
    arb_init();
    port_log("pdcp-fw: reference arbitrator started");
    for (;;) {
        pump();
        hl_service();
        arb_step();
    }
}
