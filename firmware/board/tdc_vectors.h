/*
 * tdc_vectors.h - the Cortex-M vector table of every board (ARMv7-M /
 * ARMv8-M: initial SP, then the 15 system exceptions, then the board's
 * external interrupts): Reset_Handler, the crt0's default handler for
 * every fault and system exception the core has (the reserved entries 7-10
 * and 13 stay 0), no external interrupt used yet.  The board's startup file
 * writes TDC_VECTORS(number of external interrupts) once and defines
 * Reset_Handler; its linker script places .vectors where the core reads it
 * at reset.
 */
#ifndef TDC_VECTORS_H
#define TDC_VECTORS_H

#include <stdint.h>

#include "tdc_crt0.h"

extern uint32_t __stack_top[];
void Reset_Handler(void);

/* TDC_VECTORS_FAULT(n, fault): the same table with HardFault, MemManage,
 * BusFault and UsageFault (exceptions 3-6) sent to `fault`, for a board
 * whose fault handler reports the fault registers before it resets.
 * TDC_VECTORS_FAULT_IRQ(n, fault, irqn, handler): and external interrupt
 * irqn (the board's reference manual numbering) sent to `handler`. */
#define TDC_VECTORS_TABLE(n_irqs, fault, ...)                                                         \
    typedef struct {                                                                                  \
        const uint32_t *initial_sp;                                                                   \
        void (*handler[15])(void); /* exceptions 1..15 */                                             \
        void (*irq[n_irqs])(void);                                                                    \
    } tdc_vectors_t;                                                                                  \
    __attribute__((section(".vectors"), used)) const tdc_vectors_t tdc_vectors = {                    \
        __stack_top,                                                                                  \
        {Reset_Handler, tdc_crt0_default_handler, fault, fault, fault, fault, 0, 0, 0, 0,             \
         tdc_crt0_default_handler, tdc_crt0_default_handler, 0, tdc_crt0_default_handler,             \
         tdc_crt0_default_handler},                                                                   \
        {__VA_ARGS__},                                                                                \
    }
#define TDC_VECTORS_FAULT(n_irqs, fault) TDC_VECTORS_TABLE(n_irqs, fault, tdc_crt0_default_handler)
#define TDC_VECTORS_FAULT_IRQ(n_irqs, fault, irqn, irq_handler) \
    TDC_VECTORS_TABLE(n_irqs, fault, tdc_crt0_default_handler, [irqn] = irq_handler)
#define TDC_VECTORS(n_irqs) TDC_VECTORS_FAULT(n_irqs, tdc_crt0_default_handler)

#endif
