/* sdram.h - FMC SDRAM bring-up of the STM32H747I-DISCO (32 MiB IS42S32800J). */
#ifndef TDC_STM32_SDRAM_H
#define TDC_STM32_SDRAM_H

void tdc_stm32_sdram_init(void);

#endif
