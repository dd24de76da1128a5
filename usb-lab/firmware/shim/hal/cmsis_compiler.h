/*
 * CMSIS compiler and core-register helpers the OpenFFBoard firmware uses, for the host.
 *
 * cppmain.h's inIsr() reads PRIMASK and IPSR: on the host IPSR is nonzero while a simulated
 * interrupt handler runs (the TIM_FFB update thread of hal_timer.cpp), so the firmware picks its
 * FromISR paths there as it would on the chip.
 */
#ifndef SANDPAPER_LAB_CMSIS_COMPILER_H
#define SANDPAPER_LAB_CMSIS_COMPILER_H

#include <stdint.h>

#ifndef __weak
#define __weak __attribute__((weak))
#endif
#ifndef __packed
#define __packed __attribute__((packed))
#endif
#ifndef __STATIC_INLINE
#define __STATIC_INLINE static inline
#endif
#ifndef __ALIGNED
#define __ALIGNED(x) __attribute__((aligned(x)))
#endif

#ifdef __cplusplus
extern "C" {
#endif

uint32_t lab_interrupt_active(void);  // 1 while the calling thread runs a simulated interrupt

static inline uint32_t __get_PRIMASK(void) { return 0u; }
static inline uint32_t __get_IPSR(void) { return lab_interrupt_active(); }
static inline void __disable_irq(void) {}
static inline void __enable_irq(void) {}
static inline void __NOP(void) {}
static inline void __DSB(void) {}
static inline void __ISB(void) {}

#ifdef __cplusplus
}
#endif

#endif  // SANDPAPER_LAB_CMSIS_COMPILER_H
