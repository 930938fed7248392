//! Parquet tables read back with the `parquet` crate's own reader: every value bit for bit
//! (signed zeros, subnormals, infinities and NaN included), nulls where undefined, the schema's
//! types and the footer's key-value metadata.

use parquet::basic::{LogicalType, Type as Physical};
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::record::Field;
use tumble_output::table::{Column, Format, Table, TableError, Values};

fn sample() -> Table {
    Table {
        columns: vec![
            Column {
                name: "index".into(),
                values: Values::I64(vec![0, 1, -7, i64::MAX]),
            },
            Column {
                name: "t".into(),
                values: Values::F64(vec![0.0, -0.0, 5e-324, 0.1 + 0.2]),
            },
            Column {
                name: "metric".into(),
                values: Values::OptionalF64(vec![
                    Some(f64::INFINITY),
                    None,
                    Some(f64::NAN),
                    Some(-1.0 / 3.0),
                ]),
            },
            Column {
                name: "reason".into(),
                values: Values::Text(vec![
                    "".into(),
                    "a, \"quoted\"\nline".into(),
                    "é".into(),
                    "x".into(),
                ]),
            },
        ],
        metadata: vec![
            ("tumble".into(), "{\"scene\": \"free-hoop\"}".into()),
            ("other".into(), String::new()),
        ],
    }
}

#[test]
fn parquet_round_trip_keeps_every_value_bit_for_bit_with_types_and_metadata() {
    let table = sample();
    let bytes = table.to_parquet().unwrap();
    let reader = SerializedFileReader::new(bytes::Bytes::from(bytes)).unwrap();
    let meta = reader.metadata().file_metadata();
    assert_eq!(meta.num_rows(), 4);
    let kv: Vec<(String, Option<String>)> = meta
        .key_value_metadata()
        .unwrap()
        .iter()
        .map(|kv| (kv.key.clone(), kv.value.clone()))
        .collect();
    for (k, v) in &table.metadata {
        assert!(
            kv.contains(&(k.clone(), Some(v.clone()))),
            "{k} missing in {kv:?}"
        );
    }
    let fields = meta.schema_descr().columns().to_vec();
    let types: Vec<(String, Physical, Option<LogicalType>)> = fields
        .iter()
        .map(|c| {
            (
                c.name().to_string(),
                c.physical_type(),
                c.logical_type_ref().cloned(),
            )
        })
        .collect();
    assert_eq!(types[0].1, Physical::INT64);
    assert_eq!(types[1].1, Physical::DOUBLE);
    assert_eq!(types[2].1, Physical::DOUBLE);
    assert!(fields[2].self_type().is_optional() && !fields[1].self_type().is_optional());
    assert_eq!(types[3].1, Physical::BYTE_ARRAY);
    assert_eq!(types[3].2, Some(LogicalType::String));

    let rows: Vec<Vec<Field>> = reader
        .get_row_iter(None)
        .unwrap()
        .map(|r| {
            r.unwrap()
                .into_columns()
                .into_iter()
                .map(|(_, f)| f)
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), 4);
    for (k, row) in rows.iter().enumerate() {
        let Values::I64(index) = &table.columns[0].values else {
            unreachable!()
        };
        assert_eq!(row[0], Field::Long(index[k]));
        let Values::F64(t) = &table.columns[1].values else {
            unreachable!()
        };
        let Field::Double(x) = row[1] else {
            panic!("{:?}", row[1])
        };
        assert_eq!(x.to_bits(), t[k].to_bits());
        let Values::OptionalF64(m) = &table.columns[2].values else {
            unreachable!()
        };
        match (m[k], &row[2]) {
            (None, Field::Null) => {}
            (Some(want), Field::Double(got)) => assert_eq!(got.to_bits(), want.to_bits()),
            (want, got) => panic!("row {k}: {want:?} read back as {got:?}"),
        }
        let Values::Text(s) = &table.columns[3].values else {
            unreachable!()
        };
        assert_eq!(row[3], Field::Str(s[k].clone()));
    }
}

#[test]
fn columns_of_different_lengths_are_refused_naming_the_column() {
    let mut table = sample();
    table.columns[1].values = Values::F64(vec![1.0]);
    let err = table.to_parquet().unwrap_err();
    assert!(matches!(err, TableError::Ragged { ref name, len: 1, expected: 4 } if name == "t"));
    assert!(err.to_string().contains("`t` has 1 values"), "{err}");
}

#[test]
fn the_extension_chooses_parquet_and_everything_else_is_csv() {
    assert_eq!(Format::of_path("a/b.parquet".as_ref()), Format::Parquet);
    assert_eq!(Format::of_path("b.PARQUET".as_ref()), Format::Parquet);
    assert_eq!(Format::of_path("b.csv".as_ref()), Format::Csv);
    assert_eq!(Format::of_path("-".as_ref()), Format::Csv);
    assert_eq!(Format::parse("Parquet"), Some(Format::Parquet));
    assert_eq!(Format::parse("xlsx"), None);
}
