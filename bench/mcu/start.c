/* Start-up on the mps2-an386 board: the vector table (the stack's top, the reset handler), the FPU
   switched on, .bss zeroed, newlib's semihosting (printf and exit reach QEMU's console), main. */
#include <stdlib.h>
#include <string.h>

extern int main(void);
extern void initialise_monitor_handles(void);
extern char __bss_start__[], __bss_end__[], __stack[];
void reset(void);
void _init(void);
void _fini(void);

__attribute__((section(".vectors"), used)) static void *const vectors[2] = {__stack, (void *)reset};

void reset(void)
{
    *(volatile unsigned *)0xE000ED88 |= 0xFu << 20; /* CPACR: full access to CP10 and CP11, the FPU */
    __asm volatile("dsb\n\tisb");
    memset(__bss_start__, 0, (size_t)(__bss_end__ - __bss_start__));
    initialise_monitor_handles();
    exit(main());
}

void _init(void) {}
void _fini(void) {}
