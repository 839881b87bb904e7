/*
 * tdc_ffs.h - the USB protocol on a Linux FunctionFS function (tdc_ffs.c).
 */
#ifndef TDC_FFS_H
#define TDC_FFS_H

#include <linux/usb/functionfs.h>
#include <pthread.h>

#include "tdc_usbproto.h"

/* Writes the function's descriptors and strings to ep0 (FunctionFS v2
 * format); 0, or -1 with errno. */
int tdc_ffs_write_descriptors(int ep0);

/* Serves one SETUP event with the protocol state proto (under lock): the
 * data stage, the reply or a stall.  on_reset(why) runs under the lock when
 * the request asked the board to reset (RESET_BOARD, DFU_DETACH). */
void tdc_ffs_setup(int ep0, const struct usb_ctrlrequest *c, tdc_usbp_t *proto, pthread_mutex_t *lock,
                   void (*on_reset)(const char *why));

/* Bulk IN (ep2_path): a status report always queued, each write completing
 * when the host reads it; reopens the endpoint after an unplug.  Never
 * returns: a thread's body. */
void tdc_ffs_status_loop(const char *ep2_path, tdc_usbp_t *proto, pthread_mutex_t *lock);

#endif
