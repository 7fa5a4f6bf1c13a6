"""Host-link test tools: the conformance suite and a UART-speed relay."""
