//! Placeholder: the Cortex-M example is being written.
#![no_std]
#![no_main]
